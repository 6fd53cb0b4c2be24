#include "datasets/io/carmen_writer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <vector>

#include "datasets/io/carmen_laser.h"
#include "datasets/io/number_format.h"
#include "datasets/io/text_writer.h"

namespace locbench::io {
namespace {

constexpr double kBearingTolerance = 1e-9;  // [rad]

[[noreturn]] void reject(const std::string& what) { throw std::invalid_argument("write_carmen_log: " + what); }

bool has_space(const std::string& s) {
  return std::any_of(s.begin(), s.end(),
                     [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; });
}

// A record's time.
double time_of(const EncoderReading& r) { return r.t; }
double time_of(const OdometryReading& r) { return r.t; }
double time_of(const CompassReading& r) { return r.t; }
double time_of(const TruePose& r) { return r.t; }
double time_of(const LaserReading& r) { return r.scan.timestamp; }

template <typename Records>
void check_order(const Records& records, const char* type) {
  for (std::size_t i = 1; i < records.size(); ++i) {
    if (time_of(records[i]) < time_of(records[i - 1])) {
      reject(std::string(type) + " " + std::to_string(i) + " goes back in time");
    }
  }
}

void check_finite(std::initializer_list<double> values, const char* type, std::size_t i) {
  for (const double v : values) {
    if (!std::isfinite(v)) reject(std::string(type) + " " + std::to_string(i) + " has a non-finite value");
  }
}

void check_log(const Log& log) {
  check_order(log.encoders, "ENCODER");
  check_order(log.odometry, "ODOM");
  check_order(log.compass, "COMPASS");
  check_order(log.truth, "TRUEPOS");
  check_order(log.laser, "FLASER");
  for (std::size_t i = 0; i < log.encoders.size(); ++i) check_finite({log.encoders[i].t}, "ENCODER", i);
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    const auto& r = log.odometry[i];
    check_finite({r.t, r.pose.x, r.pose.y, r.pose.theta, r.tv, r.rv}, "ODOM", i);
  }
  for (std::size_t i = 0; i < log.compass.size(); ++i) {
    check_finite({log.compass[i].t, log.compass[i].heading}, "COMPASS", i);
  }
  for (std::size_t i = 0; i < log.truth.size(); ++i) {
    const auto& r = log.truth[i];
    check_finite({r.t, r.pose.x, r.pose.y, r.pose.theta, r.odom_pose.x, r.odom_pose.y, r.odom_pose.theta}, "TRUEPOS",
                 i);
  }
  CarmenLaserSetup declared;
  try {
    declared = carmen_laser_setup(log.params);
  } catch (const std::invalid_argument&) {
    // reported by params_for
  }
  for (std::size_t i = 0; i < log.laser.size(); ++i) {
    const auto& r = log.laser[i];
    check_finite({r.scan.timestamp, r.pose.x, r.pose.y, r.pose.theta, r.odom_pose.x, r.odom_pose.y, r.odom_pose.theta},
                 "FLASER", i);
    if (r.scan.ranges.empty()) reject("FLASER " + std::to_string(i) + " has no ranges");
    for (const double v : r.scan.ranges) {
      if (!std::isfinite(v) || v < 0.0) {
        reject("FLASER " + std::to_string(i) + " has a range that is negative or not finite");
      }
    }
    const auto expected = carmen_bearings(r.scan.ranges.size(), declared);
    bool same = r.scan.bearings.size() == expected.size();
    for (std::size_t k = 0; same && k < expected.size(); ++k) {
      same = std::abs(r.scan.bearings[k] - expected[k]) <= kBearingTolerance;
    }
    if (!same) {
      reject("FLASER " + std::to_string(i) +
             ": bearings must follow the FLASER convention (n beams over 180° from −90°) or the "
             "field of view and resolution the PARAM records declare");
    }
  }
  for (const auto& [name, value] : log.params) {
    if (name.empty() || value.empty() || has_space(name) || has_space(value)) {
      reject("PARAM '" + name + "': names and values must be non-empty and without whitespace");
    }
  }
}

// log.params, with the laser PARAM records made to agree with the scans.
std::map<std::string, std::string> params_for(const Log& log) {
  std::map<std::string, std::string> params = log.params;
  CarmenLaserSetup declared;
  try {
    declared = carmen_laser_setup(params);
  } catch (const std::invalid_argument& e) {
    reject(e.what());
  }
  if (log.laser.empty()) return params;
  const Scan& first = log.laser.front().scan;
  for (const auto& r : log.laser) {
    const Pose2& a = r.scan.sensor_pose;
    const Pose2& b = first.sensor_pose;
    if (r.scan.max_range != first.max_range || a.x != b.x || a.y != b.y || a.theta != b.theta) {
      reject("FLASER scans must share one max range and sensor pose (they are PARAM records)");
    }
  }
  if (!std::isfinite(first.max_range) || !(first.max_range > 0.0) || !std::isfinite(first.sensor_pose.x) ||
      !std::isfinite(first.sensor_pose.y) || !std::isfinite(first.sensor_pose.theta)) {
    reject("FLASER max range must be finite and positive, and the sensor pose finite");
  }
  auto set = [&](std::string_view name, double value) {
    std::string text;
    append_number(text, value);
    params[std::string(name)] = text;
  };
  if (declared.max_range != first.max_range) set(kParamLaserMaxRange, first.max_range);
  const Pose2& want = first.sensor_pose;
  const Pose2& have = declared.sensor_pose;
  if (want.x != have.x) set(kParamLaserOffset, want.x);
  if (want.y != have.y) set(kParamLaserSideOffset, want.y);
  if (want.theta != have.theta) set(kParamLaserAngularOffset, want.theta);
  return params;
}

// Formats records into text chunks handed to `sink`.
class Formatter {
 public:
  explicit Formatter(std::function<void(std::string_view)> sink) : sink_(std::move(sink)) {}

  void number(double v) {
    append_number(buf_, v);
    buf_.push_back(' ');
  }
  void integer(std::int64_t v) {
    append_number(buf_, v);
    buf_.push_back(' ');
  }
  void text(std::string_view s) {
    buf_.append(s);
    buf_.push_back(' ');
  }
  void pose(const Pose2& p) {
    number(p.x);
    number(p.y);
    number(p.theta);
  }
  // A record's fields after its tag: numbers, integers, text, poses (x y θ) and lists of numbers.
  void field(double v) { number(v); }
  void field(std::int64_t v) { integer(v); }
  void field(std::string_view s) { text(s); }
  void field(const Pose2& p) { pose(p); }
  void field(const std::vector<double>& values) {
    for (const double v : values) number(v);
  }
  template <typename... Fields>
  void fields(const Fields&... f) {
    (field(f), ...);
  }
  // timestamp host logger_timestamp, end of line.
  void end_record(double t) {
    number(t);
    buf_.append("locbench ");
    append_number(buf_, t);
    buf_.push_back('\n');
    if (buf_.size() >= (std::size_t{1} << 20)) flush();
  }
  void line(std::string_view s) {
    buf_.append(s);
    buf_.push_back('\n');
  }
  void flush() {
    if (!buf_.empty()) sink_(buf_);
    buf_.clear();
  }

 private:
  std::function<void(std::string_view)> sink_;
  std::string buf_;
};

// One record type as written: its tag and fields in CARMEN's order (ODOM's accel is not kept).
void write_record(const EncoderReading& r, Formatter& out) { out.fields("ENCODER", r.left, r.right); }
void write_record(const OdometryReading& r, Formatter& out) { out.fields("ODOM", r.pose, r.tv, r.rv, 0.0); }
void write_record(const CompassReading& r, Formatter& out) { out.fields("COMPASS", r.heading); }
void write_record(const TruePose& r, Formatter& out) { out.fields("TRUEPOS", r.pose, r.odom_pose); }
void write_record(const LaserReading& r, Formatter& out) {
  const auto n = static_cast<std::int64_t>(r.scan.ranges.size());
  out.fields("FLASER", n, r.scan.ranges, r.pose, r.odom_pose);
}

void format(const Log& log, const std::map<std::string, std::string>& params, Formatter& out) {
  out.line("# CARMEN log written by locbench; see datasets/FORMAT.md");
  for (const auto& [name, value] : params) {
    out.fields("PARAM", name, value);
    out.end_record(0.0);
  }
  // Records merged by time; ties keep this type order and the order within each type.
  struct Entry {
    double t;
    std::function<void()> write;
  };
  std::vector<Entry> entries;
  entries.reserve(log.encoders.size() + log.odometry.size() + log.compass.size() + log.truth.size() + log.laser.size());
  const auto add = [&](const auto& records) {
    for (const auto& r : records) {
      entries.push_back({time_of(r), [&r, &out] {
                           write_record(r, out);
                           out.end_record(time_of(r));
                         }});
    }
  };
  add(log.encoders);
  add(log.odometry);
  add(log.compass);
  add(log.truth);
  add(log.laser);
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.t < b.t; });
  for (const Entry& e : entries) e.write();
  out.flush();
}

}  // namespace

void write_carmen_log(const Log& log, const std::filesystem::path& path) {
  check_log(log);  // before creating the file
  const auto params = params_for(log);
  TextWriter writer(path);
  Formatter out([&](std::string_view chunk) { writer.write(chunk); });
  format(log, params, out);
  writer.close();
}

std::string format_carmen_log(const Log& log) {
  check_log(log);
  const auto params = params_for(log);
  std::string text;
  Formatter out([&](std::string_view chunk) { text.append(chunk); });
  format(log, params, out);
  return text;
}

}  // namespace locbench::io
