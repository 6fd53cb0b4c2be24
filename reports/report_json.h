#pragma once
// Report ⇄ JSON (schema: reports/report.schema.json) and writing report files.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "reports/report.h"

namespace locbench::reports {

nlohmann::json to_json(const Report& report);
// Parses a report written by to_json; InputError (naming `source`) on a missing or mistyped field.
Report report_from_json(const nlohmann::json& j, const std::string& source);

// Writes the report as indented JSON, creating parent folders; returns the path written.
std::filesystem::path write_report(const Report& report, const std::filesystem::path& path);
// Reads and parses a report file.
Report read_report(const std::filesystem::path& path);

}  // namespace locbench::reports
