#include "datasets/io/censi_results_reader.h"

#include <cmath>

#include "core/errors.h"
#include "datasets/io/json_line.h"
#include "datasets/io/line_reader.h"

namespace locbench::io {
namespace {

CensiPublishedResult read_text(LineReader& reader) {
  // The file is one JSON object, possibly spread over several lines: gather them all.
  std::string text;
  std::string_view line;
  std::size_t first = 0;
  while (reader.next(line)) {
    if (first == 0 && line.find_first_not_of(" \t\r\v\f") != std::string_view::npos) {
      first = reader.line_number();
    }
    if (first != 0) {
      text.append(line);
      text.push_back('\n');
    }
  }
  const std::string& file = reader.source();
  const nlohmann::json j = parse_json_value(text, file, first);
  if (!j.is_object()) throw InputError(file, first, "expected a JSON object");
  CensiPublishedResult r;
  r.axle = json_finite(j, "axle", file, first);
  r.left_diameter = json_finite(j, "l_diam", file, first);
  r.right_diameter = json_finite(j, "r_diam", file, first);
  r.sensor_x = json_finite(j, "l_x", file, first);
  r.sensor_y = json_finite(j, "l_y", file, first);
  r.sensor_theta = json_finite(j, "l_theta", file, first);
  r.E_d = json_finite(j, "E_d", file, first);
  r.E_b = json_finite(j, "E_b", file, first);
  const auto it = j.find("covariance");
  if (it == j.end()) throw InputError(file, first, "missing key \"covariance\"");
  if (!it->is_array() || it->size() != 6) {
    throw InputError(file, first, "\"covariance\": expected an array of 6 rows");
  }
  for (int i = 0; i < 6; ++i) {
    const std::string key = "covariance[" + std::to_string(i) + "]";
    const nlohmann::json row = nlohmann::json::object({{key, (*it)[static_cast<std::size_t>(i)]}});
    double values[6];
    json_finite_array(row, key.c_str(), values, 6, file, first);
    for (int k = 0; k < 6; ++k) r.covariance(i, k) = values[k];
  }
  for (int i = 0; i < 6; ++i) {
    if (!(r.covariance(i, i) > 0.0)) {
      throw InputError(file, first, "\"covariance\": diagonal entry " + std::to_string(i) + " must be > 0");
    }
    for (int k = 0; k < i; ++k) {
      const double a = r.covariance(i, k), b = r.covariance(k, i);
      if (std::abs(a - b) > 1e-6 * std::max(std::abs(a), std::abs(b)) + 1e-300) {
        throw InputError(file, first,
                         "\"covariance\": not symmetric at (" + std::to_string(i) + ", " + std::to_string(k) + ")");
      }
    }
  }
  return r;
}

}  // namespace

double CensiPublishedResult::standard_error(int i) const { return std::sqrt(covariance(i, i)); }

CensiPublishedResult read_censi_results(const std::filesystem::path& path) { return read_lines_of(path, read_text); }

CensiPublishedResult parse_censi_results(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_text);
}

}  // namespace locbench::io
