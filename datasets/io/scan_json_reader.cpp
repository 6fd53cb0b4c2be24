#include "datasets/io/scan_json_reader.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_file.h"
#include "datasets/io/line_reader.h"

namespace locbench::io {
namespace {

std::vector<double> numbers(const nlohmann::json& j, const char* key, const std::string& file) {
  if (!j.contains(key) || !j.at(key).is_array()) {
    throw InputError(file, 0, std::string("an array \"") + key + "\" of numbers");
  }
  std::vector<double> v;
  for (const auto& x : j.at(key)) {
    if (!x.is_number()) throw InputError(file, 0, std::string("numbers only in \"") + key + "\"");
    v.push_back(x.get<double>());
  }
  return v;
}

}  // namespace

Scan read_scan_json(const std::filesystem::path& path) {
  const std::string file = path.string();
  LineReader reader(path, static_cast<std::uint64_t>(limits::kJsonFileBytes.max));  // JSON, maybe gzip
  std::string text;
  std::string_view line;
  while (reader.next(line)) {
    text.append(line);
    text.push_back('\n');
  }
  const nlohmann::json j = parse_json_text(text, file);
  if (!j.is_object()) throw InputError(file, 0, "a JSON object with \"ranges\"");
  Scan s;
  s.ranges = numbers(j, "ranges", file);
  if (j.contains("bearings")) {
    s.bearings = numbers(j, "bearings", file);
  } else if (j.contains("angle_min") && j.contains("angle_increment") && j.at("angle_min").is_number() &&
             j.at("angle_increment").is_number()) {
    const double a0 = j.at("angle_min").get<double>(), da = j.at("angle_increment").get<double>();
    for (std::size_t i = 0; i < s.ranges.size(); ++i) s.bearings.push_back(a0 + da * static_cast<double>(i));
  } else {
    throw InputError(file, 0, "\"bearings\" or \"angle_min\" and \"angle_increment\"");
  }
  if (s.bearings.size() != s.ranges.size()) {
    throw InputError(file, 0,
                     "as many bearings as ranges (" + std::to_string(s.bearings.size()) + " bearings, " +
                         std::to_string(s.ranges.size()) + " ranges)");
  }
  if (j.contains("range_max")) {
    if (!j.at("range_max").is_number()) throw InputError(file, 0, "a number \"range_max\"");
    s.max_range = j.at("range_max").get<double>();
  }
  return s;
}

}  // namespace locbench::io
