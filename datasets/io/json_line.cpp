#include "datasets/io/json_line.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace locbench::io {
namespace {

std::string article_type_name(const nlohmann::json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  if (v.is_boolean()) return "a boolean";
  return "null";
}

}  // namespace

nlohmann::json parse_json_value(std::string_view text, const std::string& file, std::size_t first_line) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const auto breaks =
        static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at ...".
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(file, first_line + breaks, "expected JSON: " + what);
  } catch (const nlohmann::json::exception& e) {  // e.g. out_of_range: number overflow
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(file, first_line, "expected JSON: " + what);
  }
}

double json_finite(const nlohmann::json& obj, const char* key, const std::string& file, std::size_t line) {
  const auto it = obj.find(key);
  if (it == obj.end()) {
    throw InputError(file, line, std::string("missing key \"") + key + "\"");
  }
  if (!it->is_number()) {
    throw InputError(file, line, std::string("\"") + key + "\": expected a number, found " + article_type_name(*it));
  }
  const double v = it->get<double>();
  if (!std::isfinite(v)) {
    throw InputError(file, line, std::string("\"") + key + "\": expected a finite number");
  }
  return v;
}

void json_finite_array(const nlohmann::json& obj, const char* key, double* out, std::size_t n, const std::string& file,
                       std::size_t line) {
  const auto it = obj.find(key);
  if (it == obj.end()) {
    throw InputError(file, line, std::string("missing key \"") + key + "\"");
  }
  if (!it->is_array() || it->size() != n) {
    throw InputError(file, line,
                     std::string("\"") + key + "\": expected an array of " + std::to_string(n) + " numbers, found " +
                         (it->is_array() ? "an array of " + std::to_string(it->size()) : article_type_name(*it)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& v = (*it)[i];
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      throw InputError(file, line,
                       std::string("\"") + key + "\"[" + std::to_string(i) + "]: expected a finite number, found " +
                           article_type_name(v));
    }
    out[i] = v.get<double>();
  }
}

}  // namespace locbench::io
