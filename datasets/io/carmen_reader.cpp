#include "datasets/io/carmen_reader.h"

#include <array>
#include <span>
#include <vector>

#include "datasets/io/carmen_laser.h"
#include "datasets/io/dataset_name.h"
#include "datasets/io/line_reader.h"
#include "datasets/io/number_format.h"
#include "datasets/io/tokenizer.h"

namespace locbench::io {
namespace {

using Fields = std::span<const std::string_view>;

// Trailer of every record: timestamp host logger_timestamp.
constexpr std::size_t kTrailer = 3;

bool is_tag(std::string_view t) {
  auto alpha = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  if (t.empty() || !alpha(t[0])) return false;
  for (char c : t) {
    if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_') return false;
  }
  return true;
}

// Non-decreasing time within one record type.
class TimeOrder {
 public:
  void check(double t, const FieldContext& ctx) {
    if (line_ != 0 && t < last_) {
      std::string msg = "timestamp ";
      append_number(msg, t);
      msg += " goes back in time: the previous " + std::string(ctx.record) + " record (line " + std::to_string(line_) +
             ") has timestamp ";
      append_number(msg, last_);
      msg += "; times must not decrease within a record type";
      fail_input(ctx, msg);
    }
    last_ = t;
    line_ = ctx.line;
  }

 private:
  double last_ = 0.0;
  std::size_t line_ = 0;
};

class CarmenParser {
 public:
  explicit CarmenParser(const std::string& source) : source_(source) {}

  void parse_line(std::string_view line, std::size_t line_no) {
    if (is_blank_or_comment(line)) return;
    split_fields(line, tokens_);
    const std::string_view tag = tokens_[0];
    const Fields f = Fields(tokens_).subspan(1);
    const FieldContext ctx{source_, line_no, tag};
    if (tag == "ODOM") {
      odom(f, ctx);
    } else if (tag == "FLASER") {
      flaser(f, ctx);
    } else if (tag == "TRUEPOS") {
      truepos(f, ctx);
    } else if (tag == "ENCODER") {
      encoder(f, ctx);
    } else if (tag == "COMPASS") {
      compass(f, ctx);
    } else if (tag == "PARAM") {
      param(f, ctx);
    } else if (is_tag(tag)) {
      ++skipped_[std::string(tag)];
    } else {
      fail_input({source_, line_no, {}},
                 "expected a record type such as ODOM, FLASER, TRUEPOS, ENCODER, COMPASS or "
                 "PARAM, or a '#' comment, found " +
                     quote_token(tag));
    }
  }

  Log finish() {
    const CarmenLaserSetup setup = carmen_laser_setup(log_.params);  // values checked already
    for (auto& r : log_.laser) {
      r.scan.max_range = setup.max_range;
      r.scan.sensor_pose = setup.sensor_pose;
      if (setup.fov || setup.resolution) r.scan.bearings = carmen_bearings(r.scan.ranges.size(), setup);
    }
    for (const auto& [type, count] : skipped_) {
      log_.params[std::string(kSkippedRecordsParamPrefix) + type] = std::to_string(count);
    }
    return std::move(log_);
  }

 private:
  // Parses fields f[first .. first + names.size()) as numbers named `names`.
  template <std::size_t N>
  std::array<double, N> numbers(Fields f, std::size_t first, const std::array<const char*, N>& names,
                                const FieldContext& ctx) {
    std::array<double, N> v{};
    for (std::size_t i = 0; i < N; ++i) v[i] = parse_finite(f[first + i], names[i], ctx);
    return v;
  }
  // Parses the trailer starting at f[first]; returns the timestamp.
  double trailer(Fields f, std::size_t first, const FieldContext& ctx) {
    const double t = parse_finite(f[first], "timestamp", ctx);
    parse_finite(f[first + 2], "logger_timestamp", ctx);
    return t;
  }

  void odom(Fields f, const FieldContext& ctx) {
    expect_field_count(f, 6 + kTrailer, ctx);
    const auto v = numbers<6>(f, 0, {"x", "y", "theta", "tv", "rv", "accel"}, ctx);
    const double t = trailer(f, 6, ctx);
    odom_order_.check(t, ctx);
    log_.odometry.push_back({t, Pose2(v[0], v[1], v[2]), v[3], v[4]});
  }

  void truepos(Fields f, const FieldContext& ctx) {
    expect_field_count(f, 6 + kTrailer, ctx);
    const auto v = numbers<6>(f, 0, {"true_x", "true_y", "true_theta", "odom_x", "odom_y", "odom_theta"}, ctx);
    const double t = trailer(f, 6, ctx);
    truth_order_.check(t, ctx);
    log_.truth.push_back({t, Pose2(v[0], v[1], v[2]), Pose2(v[3], v[4], v[5])});
  }

  void encoder(Fields f, const FieldContext& ctx) {
    expect_field_count(f, 2 + kTrailer, ctx);
    const std::int64_t left = parse_int64(f[0], "left_ticks", ctx);
    const std::int64_t right = parse_int64(f[1], "right_ticks", ctx);
    const double t = trailer(f, 2, ctx);
    encoder_order_.check(t, ctx);
    log_.encoders.push_back({t, left, right});
  }

  void compass(Fields f, const FieldContext& ctx) {
    expect_field_count(f, 1 + kTrailer, ctx);
    const double heading = parse_finite(f[0], "heading", ctx);
    const double t = trailer(f, 1, ctx);
    compass_order_.check(t, ctx);
    log_.compass.push_back({t, heading});
  }

  void flaser(Fields f, const FieldContext& ctx) {
    if (f.empty()) fail_input(ctx, "expected the beam count n after the tag, found nothing");
    const std::int64_t n = parse_int64(f[0], "beam count n", ctx);
    if (n < 1) fail_input(ctx, "beam count n: expected at least 1, found " + std::to_string(n));
    const auto beams = static_cast<std::size_t>(n);
    if (beams > f.size() || f.size() != 1 + beams + 6 + kTrailer) {
      const std::string expected = std::to_string(1 + beams + 6 + kTrailer);
      fail_input(ctx, "expected 1 + n + 9 = " + expected + " fields after the tag for n = " + std::to_string(n) +
                          " beams, found " + std::to_string(f.size()));
    }
    LaserReading r;
    r.scan.ranges.resize(beams);
    for (std::size_t i = 0; i < beams; ++i) {
      double v = 0.0;
      if (!try_parse_finite(f[1 + i], v) || v < 0.0) {
        fail_input(ctx, "range " + std::to_string(i + 1) + " of " + std::to_string(n) +
                            ": expected a finite non-negative number [m], found " + quote_token(f[1 + i]));
      }
      r.scan.ranges[i] = v;
    }
    const auto v = numbers<6>(f, 1 + beams, {"x", "y", "theta", "odom_x", "odom_y", "odom_theta"}, ctx);
    const double t = trailer(f, 1 + beams + 6, ctx);
    laser_order_.check(t, ctx);
    r.scan.timestamp = t;
    r.scan.bearings = bearings(beams);
    r.pose = Pose2(v[0], v[1], v[2]);
    r.odom_pose = Pose2(v[3], v[4], v[5]);
    log_.laser.push_back(std::move(r));
  }

  // PARAM name value | PARAM name value host timestamp | PARAM name value timestamp host logger
  void param(Fields f, const FieldContext& ctx) {
    if (f.size() == 4) {
      parse_finite(f[3], "timestamp", ctx);
    } else if (f.size() == 5) {
      trailer(f, 2, ctx);
    } else if (f.size() != 2) {
      fail_input(ctx,
                 "expected 2 fields (name value), 4 (name value host timestamp) or 5 (name "
                 "value timestamp host logger_timestamp) after the tag, found " +
                     std::to_string(f.size()));
    }
    if (const auto problem = laser_param_problem(f[0], f[1])) {
      fail_input(ctx, std::string(f[0]) + ": " + *problem);
    }
    log_.params[std::string(f[0])] = std::string(f[1]);
  }

  const std::vector<double>& bearings(std::size_t n) {
    auto it = bearings_.find(n);
    if (it == bearings_.end()) it = bearings_.emplace(n, flaser_bearings(n)).first;
    return it->second;
  }

  const std::string& source_;
  Log log_;
  std::vector<std::string_view> tokens_;
  TimeOrder odom_order_, truth_order_, encoder_order_, compass_order_, laser_order_;
  std::map<std::string, std::size_t> skipped_;
  std::map<std::size_t, std::vector<double>> bearings_;
};

Log read_carmen_lines(LineReader& reader) {
  CarmenParser parser(reader.source());
  std::string_view line;
  while (reader.next(line)) parser.parse_line(line, reader.line_number());
  Log log = parser.finish();
  log.source = reader.source();
  log.name = dataset_name_from_file(reader.source());
  return log;
}

}  // namespace

Log read_carmen_log(const std::filesystem::path& path) { return read_lines_of(path, read_carmen_lines); }

Log parse_carmen_log(std::string_view text, const std::string& source_name) {
  return read_lines_of(text, source_name, read_carmen_lines);
}

std::map<std::string, std::size_t> skipped_record_counts(const Log& log) {
  std::map<std::string, std::size_t> counts;
  const std::string prefix(kSkippedRecordsParamPrefix);
  for (auto it = log.params.lower_bound(prefix);
       it != log.params.end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it) {
    std::int64_t n = 0;
    if (try_parse_int64(it->second, n) && n >= 0) {
      counts[it->first.substr(prefix.size())] = static_cast<std::size_t>(n);
    }
  }
  return counts;
}

}  // namespace locbench::io
