#include "datasets/io/umbmark_input_reader.h"

#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "core/errors.h"
#include "core/units.h"

namespace locbench {

using nlohmann::json;

namespace {

// Plausibility limits beyond which a value is taken to be in millimetres [m].
constexpr double kMaxWheelDiameter = 2.0;
constexpr double kMaxWheelbase = 5.0;
constexpr double kMaxSide = 100.0;
// Leg counts × nominal metres per tick must be within this fraction of the side.
constexpr double kLegTolerance = 0.25;

std::string type_name(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "boolean";
  if (v.is_number()) return "number";
  if (v.is_string()) return "string \"" + v.get<std::string>() + "\"";
  if (v.is_array()) return "array";
  return "object";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool names_non_finite(const std::string& word) {
  std::string w = lower(word);
  if (!w.empty() && (w[0] == '-' || w[0] == '+')) w.erase(0, 1);
  return w == "nan" || w == "inf" || w == "infinity";
}

// The word (letters, digits, sign) around byte offset `at`.
std::string word_at(const std::string& text, std::size_t at) {
  if (text.empty()) return {};
  at = std::min(at, text.size() - 1);
  auto part = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  };
  std::size_t b = at, e = at;
  while (b > 0 && part(text[b - 1])) --b;
  while (e < text.size() && part(text[e])) ++e;
  return text.substr(b, e - b);
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(source_, 0, path.empty() ? what : path + ": " + what);
  }

  // A JSON object whose keys must all be among `known`.
  void check_keys(const json& o, const std::string& path, const std::vector<std::string>& known) {
    if (!o.is_object()) fail(path, "expected an object, found " + type_name(o));
    for (const auto& [key, value] : o.items()) {
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        fail(join(path, key), "unknown key (expected one of: " + list + ")");
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  const json& field(const json& o, const std::string& path, const char* key) {
    if (!o.contains(key)) fail(join(path, key), "missing field");
    return o.at(key);
  }

  double number(const json& v, const std::string& path, const std::string& unit) {
    if (v.is_string() && names_non_finite(v.get<std::string>())) {
      fail(path, "is the string \"" + v.get<std::string>() +
                     "\"; NaN and Infinity are not allowed: give a finite number" + unit);
    }
    if (!v.is_number()) fail(path, "expected a number" + unit + ", found " + type_name(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) {
      fail(path, "is not a finite number (NaN and Infinity are not allowed)");
    }
    return x;
  }

  // A length in metres, > 0 and at most `max` (beyond: "looks like millimetres").
  double length(const json& o, const std::string& path, const char* key, double max) {
    const std::string p = join(path, key);
    const double x = number(field(o, path, key), p, " in metres");
    if (x <= 0.0) fail(p, fmt::format("must be > 0, got {}", x));
    if (x > max) {
      fail(p, fmt::format("{} looks like millimetres; expected metres (at most {} m)", x, max));
    }
    return x;
  }

  double positive(const json& o, const std::string& path, const char* key) {
    const std::string p = join(path, key);
    const double x = number(field(o, path, key), p, "");
    if (x <= 0.0) fail(p, fmt::format("must be > 0, got {}", x));
    return x;
  }

  std::int64_t count(const json& o, const std::string& path, const char* key) {
    const std::string p = join(path, key);
    const double x = number(field(o, path, key), p, " (encoder counts)");
    if (x != std::floor(x) || std::abs(x) > 9e15)
      fail(p, fmt::format("expected a whole number of counts, got {}", x));
    if (x <= 0.0) fail(p, fmt::format("must be > 0 (counts of one straight leg), got {}", x));
    return static_cast<std::int64_t>(x);
  }

 private:
  std::string source_;
};

json parse(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(
                text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())),
                '\n'));
    const std::string word = word_at(text, at);
    if (names_non_finite(word)) {
      throw InputError(source, line,
                       "'" + word +
                           "' is not a JSON number: NaN and Infinity are not allowed; "
                           "every value must be a finite number (lengths in metres)");
    }
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..."
    const auto colon = what.find(": ");
    throw InputError(
        source, line,
        "invalid JSON: " + (colon == std::string::npos ? what : what.substr(colon + 2)));
  } catch (const json::exception& e) {
    // out_of_range.406: "number overflow parsing '1e999'" — a literal beyond double range.
    const std::string what = e.what();
    const auto open = what.find('\'');
    const auto close = what.rfind('\'');
    std::size_t line = 0;
    std::string token;
    if (open != std::string::npos && close > open) {
      token = what.substr(open + 1, close - open - 1);
      const auto at = text.find(token);
      if (at != std::string::npos) {
        line = 1 + static_cast<std::size_t>(std::count(
                       text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
      }
    }
    throw InputError(source, line,
                     token.empty() ? "invalid JSON: " + what
                                   : "'" + token +
                                         "' is not a finite number (it overflows a "
                                         "double); every value must be finite");
  }
}

}  // namespace

UmbmarkInput parse_umbmark_input(const std::string& text, const std::string& source) {
  const json j = parse(text, source);
  Reader r(source);
  r.check_keys(j, "", {"side_length_m", "nominal", "tape_measure_scale", "leg_ticks", "runs"});

  UmbmarkInput in;
  in.side_length = r.length(j, "", "side_length_m", kMaxSide);

  const json& nom = r.field(j, "", "nominal");
  r.check_keys(nom, "nominal",
               {"wheel_diameter_m", "wheel_diameter_left_m", "wheel_diameter_right_m",
                "wheelbase_m", "gear_ratio", "counts_per_rev"});
  const bool per_wheel =
      nom.contains("wheel_diameter_left_m") || nom.contains("wheel_diameter_right_m");
  if (per_wheel && nom.contains("wheel_diameter_m")) {
    r.fail("nominal",
           "give either wheel_diameter_m or wheel_diameter_left_m and "
           "wheel_diameter_right_m, not both");
  }
  if (per_wheel) {
    in.nominal.diameter_left = r.length(nom, "nominal", "wheel_diameter_left_m", kMaxWheelDiameter);
    in.nominal.diameter_right =
        r.length(nom, "nominal", "wheel_diameter_right_m", kMaxWheelDiameter);
  } else {
    in.nominal.diameter_left = r.length(nom, "nominal", "wheel_diameter_m", kMaxWheelDiameter);
    in.nominal.diameter_right = in.nominal.diameter_left;
  }
  in.nominal.wheelbase = r.length(nom, "nominal", "wheelbase_m", kMaxWheelbase);
  in.encoder.gear_ratio = r.positive(nom, "nominal", "gear_ratio");
  in.encoder.counts_per_rev = r.positive(nom, "nominal", "counts_per_rev");

  if (j.contains("tape_measure_scale")) {
    in.tape_measure_scale = r.positive(j, "", "tape_measure_scale");
    if (in.tape_measure_scale < 0.5 || in.tape_measure_scale > 2.0) {
      r.fail("tape_measure_scale",
             fmt::format("{} is not a plausible E_s = D_a/D_n (a ratio near 1, e.g. 1.003)",
                         in.tape_measure_scale));
    }
  }

  const json& legs = r.field(j, "", "leg_ticks");
  r.check_keys(legs, "leg_ticks", {"left", "right"});
  in.leg_ticks_left = r.count(legs, "leg_ticks", "left");
  in.leg_ticks_right = r.count(legs, "leg_ticks", "right");
  const RobotParams robot{in.nominal, in.nominal, in.encoder};
  for (const auto& [key, ticks, diameter] :
       {std::tuple{"left", in.leg_ticks_left, in.nominal.diameter_left},
        std::tuple{"right", in.leg_ticks_right, in.nominal.diameter_right}}) {
    const double c = robot.meters_per_tick(diameter);
    const double travel = static_cast<double>(ticks) * c;
    if (std::abs(travel / in.side_length - 1.0) > kLegTolerance) {
      r.fail(std::string("leg_ticks.") + key,
             fmt::format("{} counts are {:.3f} m at the nominal {:.3f} mm per tick, but "
                         "side_length_m is {} m; leg_ticks are the counts of one straight leg "
                         "(about {:.0f} here)",
                         ticks, travel, to_mm(c), in.side_length, in.side_length / c));
    }
  }

  const json& runs = r.field(j, "", "runs");
  if (!runs.is_array()) r.fail("runs", "expected an array of runs, found " + type_name(runs));
  if (runs.empty()) {
    r.fail("runs",
           "is empty: UMBmark needs return errors of runs in both directions "
           "(normally 5 clockwise and 5 counter-clockwise)");
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string path = fmt::format("runs[{}]", i);
    const json& run = runs[i];
    r.check_keys(run, path, {"direction", "x_error_m", "y_error_m"});
    const json& dir = r.field(run, path, "direction");
    UmbmarkReturn ret;
    if (dir == "cw") {
      ret.direction = UmbmarkDirection::kClockwise;
    } else if (dir == "ccw") {
      ret.direction = UmbmarkDirection::kCounterClockwise;
    } else {
      r.fail(path + ".direction", "expected \"cw\" or \"ccw\", found " + type_name(dir));
    }
    for (const char* key : {"x_error_m", "y_error_m"}) {
      const std::string p = path + "." + key;
      const double e = r.number(r.field(run, path, key), p, " in metres");
      if (std::abs(e) > in.side_length) {
        r.fail(p, fmt::format("{} is longer than the side ({} m): looks like millimetres; "
                              "expected metres",
                              e, in.side_length));
      }
      (key[0] == 'x' ? ret.x_error : ret.y_error) = e;
    }
    in.runs.push_back(ret);
  }
  const UmbmarkCentroids c = umbmark_centroids(in.runs);
  if (c.runs_cw == 0 || c.runs_ccw == 0) {
    r.fail("runs", fmt::format("has {} clockwise and {} counter-clockwise runs: UMBmark needs "
                               "both directions (normally 5 each)",
                               c.runs_cw, c.runs_ccw));
  }
  return in;
}

UmbmarkInput read_umbmark_input(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, 0, "cannot open UMBmark input file");
  std::ostringstream text;
  text << f.rdbuf();
  return parse_umbmark_input(text.str(), path);
}

}  // namespace locbench
