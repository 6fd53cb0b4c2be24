#pragma once
// Strict access to JSON values read from line-based files, with InputError(file, line, ...)
// messages: parsing, required finite numbers, fixed-size number arrays.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace locbench::io {

// Parses `text` as one JSON value. A syntax error becomes InputError at `first_line` plus the
// number of line breaks before the error's byte.
nlohmann::json parse_json_value(std::string_view text, const std::string& file, std::size_t first_line);

// obj[key] as a finite number; InputError naming the key when absent, not a number or not
// finite. `obj` must be an object.
double json_finite(const nlohmann::json& obj, const char* key, const std::string& file, std::size_t line);

// obj[key] as an array of exactly n finite numbers, written to out[0..n).
void json_finite_array(const nlohmann::json& obj, const char* key, double* out, std::size_t n, const std::string& file,
                       std::size_t line);

}  // namespace locbench::io
