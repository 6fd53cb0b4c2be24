#include "datasets/io/umbmark_input_reader.h"

#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/errors.h"
#include "core/json_file.h"
#include "core/json_options.h"
#include "core/units.h"

namespace locbench::io {

using nlohmann::json;

namespace {

// Plausibility limits beyond which a value is taken to be in millimetres [m].
constexpr double kMaxWheelDiameter = 2.0;
constexpr double kMaxWheelbase = 5.0;
constexpr double kMaxSide = 100.0;
// Leg counts × nominal metres per tick must be within this fraction of the side.
constexpr double kLegTolerance = 0.25;

std::string described(const json& v) {
  if (v.is_string()) return "string \"" + v.get<std::string>() + "\"";
  return json_type_name(v);
}

bool names_non_finite(std::string w) {
  std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!w.empty() && (w[0] == '-' || w[0] == '+')) w.erase(0, 1);
  return w == "nan" || w == "inf" || w == "infinity";
}

// The required, unit-checked fields of one object of the file, on the strict reader.
class ObjectFields {
 public:
  ObjectFields(const json& j, std::string path, const std::string& source, std::initializer_list<const char*> keys)
      : r_(j, std::move(path), source) {
    r_.allow_only(keys);
  }

  StrictJsonReader& reader() { return r_; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const { r_.fail(key, what); }

  double number(const char* key, const std::string& unit) {
    const json& v = r_.required(key);
    if (v.is_string() && names_non_finite(v.get<std::string>())) {
      fail(key, "is the string \"" + v.get<std::string>() +
                    "\"; NaN and Infinity are not allowed: give a finite number" + unit);
    }
    if (!v.is_number()) fail(key, "expected a number" + unit + ", found " + described(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "is not a finite number (NaN and Infinity are not allowed)");
    return x;
  }

  // A length in metres, > 0 and at most `max` (beyond: "looks like millimetres").
  double length(const char* key, double max) {
    const double x = number(key, " in metres");
    if (x <= 0.0) fail(key, fmt::format("must be > 0, got {}", x));
    if (x > max) {
      fail(key, fmt::format("{} looks like millimetres; expected metres (at most {} m)", x, max));
    }
    return x;
  }

  double positive(const char* key) {
    const double x = number(key, "");
    if (x <= 0.0) fail(key, fmt::format("must be > 0, got {}", x));
    return x;
  }

  std::int64_t count(const char* key) {
    const double x = number(key, " (encoder counts)");
    if (x != std::floor(x) || std::abs(x) > 9e15)
      fail(key, fmt::format("expected a whole number of counts, got {}", x));
    if (x <= 0.0) fail(key, fmt::format("must be > 0 (counts of one straight leg), got {}", x));
    return static_cast<std::int64_t>(x);
  }

 private:
  StrictJsonReader r_;
};

}  // namespace

UmbmarkInput umbmark_input_from_json(const json& j, const std::string& source) {
  ObjectFields r(j, "", source, {"side_length_m", "nominal", "tape_measure_scale", "leg_ticks", "runs"});

  UmbmarkInput in;
  in.side_length = r.length("side_length_m", kMaxSide);

  const json& nom = r.reader().required("nominal");
  ObjectFields n(nom, "nominal", source,
                 {"wheel_diameter_m", "wheel_diameter_left_m", "wheel_diameter_right_m", "wheelbase_m", "gear_ratio",
                  "counts_per_rev"});
  const bool per_wheel = nom.contains("wheel_diameter_left_m") || nom.contains("wheel_diameter_right_m");
  if (per_wheel && nom.contains("wheel_diameter_m")) {
    r.fail("nominal",
           "give either wheel_diameter_m or wheel_diameter_left_m and "
           "wheel_diameter_right_m, not both");
  }
  if (per_wheel) {
    in.nominal.diameter_left = n.length("wheel_diameter_left_m", kMaxWheelDiameter);
    in.nominal.diameter_right = n.length("wheel_diameter_right_m", kMaxWheelDiameter);
  } else {
    in.nominal.diameter_left = n.length("wheel_diameter_m", kMaxWheelDiameter);
    in.nominal.diameter_right = in.nominal.diameter_left;
  }
  in.nominal.wheelbase = n.length("wheelbase_m", kMaxWheelbase);
  in.encoder.gear_ratio = n.positive("gear_ratio");
  in.encoder.counts_per_rev = n.positive("counts_per_rev");

  if (j.contains("tape_measure_scale")) {
    in.tape_measure_scale = r.positive("tape_measure_scale");
    if (in.tape_measure_scale < 0.5 || in.tape_measure_scale > 2.0) {
      r.fail("tape_measure_scale",
             fmt::format("{} is not a plausible E_s = D_a/D_n (a ratio near 1, e.g. 1.003)", in.tape_measure_scale));
    }
  }

  ObjectFields legs(r.reader().required("leg_ticks"), "leg_ticks", source, {"left", "right"});
  in.leg_ticks_left = legs.count("left");
  in.leg_ticks_right = legs.count("right");
  const RobotParams robot{in.nominal, in.nominal, in.encoder};
  for (const auto& [key, ticks, diameter] : {std::tuple{"left", in.leg_ticks_left, in.nominal.diameter_left},
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

  const json& runs = r.reader().required("runs");
  if (!runs.is_array()) r.fail("runs", "expected an array of runs, found " + described(runs));
  if (runs.empty()) {
    r.fail("runs",
           "is empty: UMBmark needs return errors of runs in both directions "
           "(normally 5 clockwise and 5 counter-clockwise)");
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string path = fmt::format("runs[{}]", i);
    ObjectFields run(runs[i], path, source, {"direction", "x_error_m", "y_error_m"});
    const json& dir = run.reader().required("direction");
    UmbmarkReturn ret;
    if (dir == "cw") {
      ret.direction = UmbmarkDirection::kClockwise;
    } else if (dir == "ccw") {
      ret.direction = UmbmarkDirection::kCounterClockwise;
    } else {
      run.fail("direction", "expected \"cw\" or \"ccw\", found " + described(dir));
    }
    for (const char* key : {"x_error_m", "y_error_m"}) {
      const double e = run.number(key, " in metres");
      if (std::abs(e) > in.side_length) {
        run.fail(key, fmt::format("{} is longer than the side ({} m): looks like millimetres; "
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

UmbmarkInput parse_umbmark_input(const std::string& text, const std::string& source) {
  return umbmark_input_from_json(parse_json_text(text, source), source);
}

UmbmarkInput read_umbmark_input(const std::string& path) {
  return umbmark_input_from_json(read_json_file(path, "UMBmark input file (JSON)"), path);
}

}  // namespace locbench::io
