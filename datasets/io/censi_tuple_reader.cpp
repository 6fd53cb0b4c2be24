#include "datasets/io/censi_tuple_reader.h"

#include <array>

#include "core/errors.h"
#include "datasets/io/json_line.h"
#include "datasets/io/line_reader.h"

namespace locbench::io {
namespace {

bool blank(std::string_view line) { return line.find_first_not_of(" \t\r\v\f") == std::string_view::npos; }

// Splits a line into its top-level JSON values: each ends where the bracket depth returns to
// zero outside strings. Unbalanced text is returned as is, for the parser to report.
std::vector<std::string_view> json_values(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = std::string_view::npos;
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (start == std::string_view::npos) {
      if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') continue;
      start = i;
    }
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if ((c == '}' || c == ']') && --depth == 0) {
      out.push_back(line.substr(start, i + 1 - start));
      start = std::string_view::npos;
    }
  }
  if (start != std::string_view::npos) out.push_back(line.substr(start));
  return out;
}

// One tuple from a parsed JSON value.
WheelSpeedTuple to_tuple(const nlohmann::json& j, const std::string& file, std::size_t n) {
  if (!j.is_object()) throw InputError(file, n, "expected a JSON object");
  WheelSpeedTuple t;
  t.T = json_finite(j, "T", file, n);
  if (!(t.T > 0.0)) throw InputError(file, n, "\"T\": expected an interval > 0 s");
  t.phi_l = json_finite(j, "phi_l", file, n);
  t.phi_r = json_finite(j, "phi_r", file, n);
  std::array<double, 3> sm{};
  json_finite_array(j, "sm", sm.data(), sm.size(), file, n);
  t.sm = Pose2(sm[0], sm[1], sm[2]);
  return t;
}

std::vector<WheelSpeedTuple> read_tuple_lines(LineReader& reader) {
  std::vector<WheelSpeedTuple> out;
  std::string_view line;
  while (reader.next(line)) {
    if (blank(line)) continue;
    const std::string& file = reader.source();
    const std::size_t n = reader.line_number();
    for (const std::string_view value : json_values(line)) {
      out.push_back(to_tuple(parse_json_value(value, file, n), file, n));
    }
  }
  if (out.empty()) throw InputError(reader.source(), 0, "no tuples");
  return out;
}

}  // namespace

std::vector<WheelSpeedTuple> read_censi_tuples(const std::filesystem::path& path) {
  return read_lines_of(path, read_tuple_lines);
}

std::vector<WheelSpeedTuple> parse_censi_tuples(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_tuple_lines);
}

}  // namespace locbench::io
