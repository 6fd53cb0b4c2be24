#pragma once
// Reading a JSON input file with errors that name it: a folder, an unreadable file, a syntax
// error (with its line), NaN/Infinity written as a number and a number beyond double range
// (1e400) are InputErrors (exit 2), never a library exception that surfaces as "internal error".
// The one place in the tree that turns a file (or text) into a nlohmann::json.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace locbench {

// `what` names the file's role in messages ("rules file", "--options file", …).
nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& what = "JSON file");

// Parses JSON text the same way; `source` names it in errors.
nlohmann::json parse_json_text(const std::string& text, const std::string& source);

}  // namespace locbench
