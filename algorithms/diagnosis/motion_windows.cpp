#include "algorithms/diagnosis/motion_windows.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <tuple>

#include "core/angle.h"
#include "core/errors.h"

namespace locbench::diagnosis {

std::string to_string(OdometryKind k) { return k == OdometryKind::kEncoder ? "encoder" : "odometry_pose"; }
std::string to_string(ReferenceKind k) {
  switch (k) {
    case ReferenceKind::kTruePose: return "truepos";
    case ReferenceKind::kRelations: return "relations";
    case ReferenceKind::kCompass: return "compass";
  }
  return "?";
}

std::string MotionData::describe() const {
  switch (reference) {
    case ReferenceKind::kTruePose:
      return fmt::format("TRUEPOS ground truth ({} poses), {} windows", truth.size(), windows.size());
    case ReferenceKind::kRelations: return fmt::format("reference relations ({} windows)", windows.size());
    case ReferenceKind::kCompass:
      return fmt::format("compass heading increments ({} readings), {} windows", compass.size(), windows.size());
  }
  return "";
}

namespace {

// The first of time-sorted `records` with time ≥ t, as std::lower_bound finds it, searched from
// where a uniform rate puts t: references are sampled at a nearly steady rate, so the guess is a
// few records off and the galloping search a few steps, where a bisection of a long log takes ~16
// steps through cold memory (the diagnosis interpolates twice per window and evaluation).
template <typename Record>
typename std::vector<Record>::const_iterator first_at_or_after(const std::vector<Record>& records, double t) {
  const auto before = [](const Record& p, double v) { return p.t < v; };
  const std::size_t n = records.size();
  const double span = records.back().t - records.front().t;
  const double share = span > 0.0 ? (t - records.front().t) / span : 0.0;
  const std::size_t guess =  // (a NaN t: the first record, as std::lower_bound gives it)
      share > 0.0 ? std::min(n - 1, static_cast<std::size_t>(std::min(share, 1.0) * static_cast<double>(n - 1))) : 0;
  std::size_t lo = guess, hi = guess + 1;  // the answer lies in [lo, hi]
  if (records[guess].t < t) {
    for (std::size_t step = 1; hi < n && records[hi].t < t; step *= 2) {
      lo = hi;
      hi = std::min(n, hi + step);
    }
  } else {
    hi = guess;
    for (std::size_t step = 1; lo > 0 && !(records[lo - 1].t < t); step *= 2) {
      hi = lo - 1;
      lo = lo > step ? lo - step : 0;
    }
  }
  const auto first = records.begin();
  return std::lower_bound(first + static_cast<std::ptrdiff_t>(lo), first + static_cast<std::ptrdiff_t>(hi), t, before);
}

// The value of time-sorted `records` at time t: value(record) at a record's own time, else
// blend(value(a), value(b), s) between the two records around t, s the fraction of the way from
// a to b; nullopt outside the records' span.
template <typename Record, typename Value, typename Blend>
auto interpolate_records(const std::vector<Record>& records, double t, Value value, Blend blend)
    -> std::optional<decltype(value(records.front()))> {
  if (records.empty() || t < records.front().t || t > records.back().t) return std::nullopt;
  auto it = first_at_or_after(records, t);
  if (it == records.begin()) return value(*it);
  const Record& b = *it;
  const Record& a = *(it - 1);
  const double dt = b.t - a.t;
  return blend(value(a), value(b), dt > 0.0 ? (t - a.t) / dt : 0.0);
}

Pose2 blend_poses(const Pose2& a, const Pose2& b, double s) {
  return Pose2(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.theta + s * angle_diff(b.theta, a.theta));
}

}  // namespace

std::optional<Pose2> interpolate_truth(const std::vector<TruePose>& truth, double t) {
  return interpolate_records(
      truth, t, [](const TruePose& p) { return p.pose; }, blend_poses);
}

std::optional<Pose2> TruthInterpolator::at(double t) {
  if (truth_.empty() || t < truth_.front().t || t > truth_.back().t) return std::nullopt;
  // Step to the first record with time ≥ t: what interpolate_records's lower_bound finds.
  next_ = std::min(next_, truth_.size() - 1);
  while (next_ + 1 < truth_.size() && truth_[next_].t < t) ++next_;
  while (next_ > 0 && truth_[next_ - 1].t >= t) --next_;
  if (next_ == 0) return truth_.front().pose;
  const TruePose& a = truth_[next_ - 1];
  const TruePose& b = truth_[next_];
  const double dt = b.t - a.t;
  return blend_poses(a.pose, b.pose, dt > 0.0 ? (t - a.t) / dt : 0.0);
}

void fill_covariates(const MotionData& m, MotionWindow& w) {
  w.distance = w.signed_distance = w.turn = w.wheel_travel = 0.0;
  const double base = m.nominal.wheelbase > 0.0 ? m.nominal.wheelbase : 0.5;
  for (std::size_t i = w.first; i < w.last; ++i) {
    const auto& s = m.steps[i];
    double dd = 0.0, dth = 0.0, travel = 0.0;
    if (m.odometry == OdometryKind::kEncoder) {
      const double ul = s.a * m.nominal.meters_per_tick_left, ur = s.b * m.nominal.meters_per_tick_right;
      dd = 0.5 * (ul + ur);
      dth = (ur - ul) / m.nominal.wheelbase;
      travel = std::abs(ul) + std::abs(ur);
    } else {
      dd = s.a;
      dth = s.b;
      travel = std::abs(dd - 0.5 * base * dth) + std::abs(dd + 0.5 * base * dth);
    }
    w.distance += std::abs(dd);
    w.signed_distance += dd;
    w.turn += dth;
    w.wheel_travel += travel;
  }
}

std::optional<double> interpolate_compass(const std::vector<CompassReading>& compass, double t) {
  return interpolate_records(
      compass, t, [](const CompassReading& c) { return c.heading; },
      [](double a, double b, double s) { return wrap_angle(a + s * angle_diff(b, a)); });
}

namespace {

// Faster than any wheeled robot the suite knows (the simulated ones drive at ≤ 1 m/s) [m/s].
constexpr double kMaxWheelSpeed = 100.0;

void check_nominal(const Log& log, const NominalModel& m) {
  auto bad = [&](const std::string& what) { throw InputError(log.source, 0, what); };
  if (!(m.wheelbase > 0.0) || !(m.meters_per_tick_left > 0.0) || !(m.meters_per_tick_right > 0.0)) {
    bad("PARAM robot_wheelbase and robot_meters_per_tick_left/right must be positive");
  }
  if (m.wheelbase > 5.0) {
    bad(fmt::format("PARAM robot_wheelbase = {} m is implausible: expected metres (not mm)", m.wheelbase));
  }
  if (m.wheelbase < 0.01) {
    bad(fmt::format("PARAM robot_wheelbase = {} m is implausible: expected at least 0.01 m", m.wheelbase));
  }
  // Real encoders give 1 µm to ~20 mm per tick (the Trilobot: 12.64 mm); 0.1 m and more is a
  // millimetre value written as metres, below 1e-9 m (or a denormal) is no encoder.
  const double mpt_max = 0.1, mpt_min = 1e-9;
  if (m.meters_per_tick_left > mpt_max || m.meters_per_tick_right > mpt_max || m.meters_per_tick_left < mpt_min ||
      m.meters_per_tick_right < mpt_min) {
    bad(
        fmt::format("PARAM robot_meters_per_tick_left/right = {}/{} are implausible: expected metres "
                    "per tick in [{}, {}) (millimetres by mistake?)",
                    m.meters_per_tick_left, m.meters_per_tick_right, mpt_min, mpt_max));
  }
}

// ΔD, Δθ between consecutive dead-reckoned poses (ΔD signed along the mid heading).
OdometryStep pose_step(const OdometryReading& a, const OdometryReading& b) {
  const double dth = angle_diff(b.pose.theta, a.pose.theta);
  const double mid = a.pose.theta + 0.5 * dth;
  const double dx = b.pose.x - a.pose.x, dy = b.pose.y - a.pose.y;
  double d = std::hypot(dx, dy);
  if (dx * std::cos(mid) + dy * std::sin(mid) < 0.0) d = -d;
  return {a.t, b.t, d, dth};
}

// The data judged before any fit: a robot that never moves gives no test any power (nothing could
// be found, so "no significant discrepancy" would mislead), and ground truth on another scale than
// the odometry is not a reference (TRUEPOS × 1e300 would get the clean log's verdict).
void check_motion_and_scale(const MotionData& m, const std::string& file) {
  double odometry_path = 0.0, odometry_turn = 0.0;
  for (const MotionWindow& w : m.windows) odometry_path += w.distance, odometry_turn += std::abs(w.turn);
  if (!(odometry_path > 1e-6) && !(odometry_turn > 1e-6)) {
    throw InputError(file, 0,
                     fmt::format("the odometry shows no motion in any of its {} windows (0 m, 0 rad): a robot "
                                 "that never moves leaves nothing to diagnose",
                                 m.windows.size()));
  }
  if (m.reference != ReferenceKind::kTruePose || !(odometry_path > 1.0)) return;
  double truth_path = 0.0;
  for (const MotionWindow& w : m.windows) {
    const auto a = interpolate_truth(m.truth, w.t0), b = interpolate_truth(m.truth, w.t1);
    if (a && b) truth_path += std::hypot(b->x - a->x, b->y - a->y);
  }
  const double ratio = truth_path / odometry_path;
  if (!(ratio > 1e-2 && ratio < 1e2)) {
    throw InputError(file, 0,
                     fmt::format("TRUEPOS travels {:.6g} m over the windows in which the odometry travels {:.6g} m "
                                 "(ratio {:.3g}): expected ground truth on the odometry's scale (metres), within a "
                                 "factor of 100",
                                 truth_path, odometry_path, ratio));
  }
}

}  // namespace

namespace {
std::atomic<std::size_t> motion_data_calls{0};
}  // namespace

std::size_t build_motion_data_calls() { return motion_data_calls.load(); }

namespace {

// Encoder steps (ΔN_L, ΔN_R), each checked for a step no wheel can make.
std::vector<OdometryStep> encoder_steps(const Log& log, const NominalModel& nominal, const std::string& file) {
  std::vector<OdometryStep> steps;
  for (std::size_t i = 1; i < log.encoders.size(); ++i) {
    const auto& a = log.encoders[i - 1];
    const auto& b = log.encoders[i];
    std::int64_t dl = 0, dr = 0;
    if (__builtin_sub_overflow(b.left, a.left, &dl) || __builtin_sub_overflow(b.right, a.right, &dr)) {
      throw InputError(file, 0,
                       fmt::format("ENCODER at t = {}: the tick counts jump by more than the "
                                   "64-bit range from the previous record",
                                   b.t));
    }
    // A step no wheel can make (a tick glitch, a counter reset) is refused with its time rather
    // than absorbed by the fits (a 1e9-tick glitch would otherwise pass with the clean verdict).
    const double travel = std::max(std::abs(static_cast<double>(dl) * nominal.meters_per_tick_left),
                                   std::abs(static_cast<double>(dr) * nominal.meters_per_tick_right));
    if (!(travel <= kMaxWheelSpeed * (b.t - a.t) + 1.0)) {
      throw InputError(file, 0,
                       fmt::format("ENCODER at t = {}: a wheel travels {:.6g} m in {:.6g} s since the previous "
                                   "record (more than {} m/s and 1 m): a tick glitch or a counter reset?",
                                   b.t, travel, b.t - a.t, kMaxWheelSpeed));
    }
    steps.push_back({a.t, b.t, static_cast<double>(dl), static_cast<double>(dr)});
  }
  return steps;
}

// The log's odometry as steps: encoder ticks, ODOM poses, or the poses logged with the scans.
MotionData odometry_of(const Log& log, const std::string& file) {
  MotionData m;
  if (!log.encoders.empty()) {
    m.odometry = OdometryKind::kEncoder;
    const auto nominal = log.nominal_model();
    if (!nominal) {
      throw InputError(file, 0,
                       "ENCODER records need the nominal model: PARAM robot_meters_per_tick_left, "
                       "robot_meters_per_tick_right and robot_wheelbase");
    }
    m.nominal = *nominal;
    check_nominal(log, m.nominal);
    m.steps = encoder_steps(log, m.nominal, file);
  } else if (log.odometry.size() >= 2) {
    m.odometry = OdometryKind::kPose;
    if (const auto nominal = log.nominal_model()) m.nominal = *nominal;
    for (std::size_t i = 1; i < log.odometry.size(); ++i) {
      m.steps.push_back(pose_step(log.odometry[i - 1], log.odometry[i]));
    }
  } else if (log.laser.size() >= 2 && !(log.laser[1].odom_pose.x == 0.0 && log.laser[1].odom_pose.y == 0.0 &&
                                        log.laser[1].odom_pose.theta == 0.0)) {
    // No ODOM records: the odometry poses logged with the scans (FLASER odom_x, odom_y, odom_θ).
    m.odometry = OdometryKind::kPose;
    for (std::size_t i = 1; i < log.laser.size(); ++i) {
      const auto& a = log.laser[i - 1];
      const auto& b = log.laser[i];
      m.steps.push_back(
          pose_step({a.scan.timestamp, a.odom_pose, 0.0, 0.0}, {b.scan.timestamp, b.odom_pose, 0.0, 0.0}));
    }
  } else {
    throw InputError(file, 0,
                     "no odometry: expected ENCODER records, at least two ODOM records or FLASER odometry poses");
  }
  return m;
}

// Merge consecutive samples into sub-steps of at least `min_step` seconds: the model is linear
// in each step's ΔN (or ΔD, Δθ), so only the arc integration within a sub-step is coarser.
std::vector<OdometryStep> merge_short_steps(std::vector<OdometryStep> steps, const WindowOptions& options) {
  if (!(options.min_step > 0.0 && steps.size() > 1)) return steps;
  std::vector<OdometryStep> merged{steps.front()};
  for (std::size_t i = 1; i < steps.size(); ++i) {
    OdometryStep& last = merged.back();
    const OdometryStep& st = steps[i];
    if (last.t1 - last.t0 < options.min_step && st.t0 == last.t1 && st.t1 - st.t0 <= options.max_gap) {
      last.t1 = st.t1;
      last.a += st.a;
      last.b += st.b;
    } else {
      merged.push_back(st);
    }
  }
  return merged;
}

// PARAM compass_resolution [rad], 0 when not declared.
double declared_compass_step(const Log& log, const std::string& file) {
  double step = 0.0;
  if (auto it = log.params.find("compass_resolution"); it != log.params.end()) {
    char* end = nullptr;
    step = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0' || !std::isfinite(step) || step < 0.0) {
      throw InputError(
          file, 0, "PARAM compass_resolution: expected a non-negative number of radians, found '" + it->second + "'");
    }
    if (step > 0.5) {
      throw InputError(file, 0,
                       fmt::format("PARAM compass_resolution = {} is implausible: expected radians "
                                   "(degrees by mistake?)",
                                   step));
    }
  }
  return step;
}

ReferenceKind reference_of(const Log& log, const std::string& file) {
  if (log.truth.size() >= 2) return ReferenceKind::kTruePose;
  if (!log.relations.empty()) return ReferenceKind::kRelations;
  if (log.compass.size() >= 2) return ReferenceKind::kCompass;
  throw InputError(file, 0,
                   "no reference to take residuals against: expected TRUEPOS ground truth, "
                   "reference relations (--relations) or COMPASS headings");
}

// One window per relation: the odometry between t1 and t2, the first and last samples cut at
// the relation's stamps (a step's ΔN or ΔD, Δθ split in proportion to time). The steps become
// the windows' cut steps.
MotionData relation_windows(MotionData m, std::vector<Relation> relations) {
  const std::vector<OdometryStep> all = std::move(m.steps);
  m.steps.clear();
  // In time order, whatever the file's line order (the held-out split depends on it).
  std::sort(relations.begin(), relations.end(), [](const Relation& x, const Relation& y) {
    return std::tie(x.t1, x.t2, x.delta.x, x.delta.y, x.delta.theta) <
           std::tie(y.t1, y.t2, y.delta.x, y.delta.y, y.delta.theta);
  });
  for (const auto& r : relations) {
    if (r.t2 - r.t1 > 10.0 || !(r.t2 > r.t1)) continue;  // local relations (loop closures span minutes)
    if (r.t1 < all.front().t0 || r.t2 > all.back().t1) continue;
    auto it =
        std::upper_bound(all.begin(), all.end(), r.t1, [](double v, const OdometryStep& st) { return v < st.t1; });
    MotionWindow w;
    w.first = m.steps.size();
    for (; it != all.end() && it->t0 < r.t2; ++it) {
      const double a = std::max(it->t0, r.t1), b = std::min(it->t1, r.t2);
      const double span = it->t1 - it->t0;
      const double f = span > 0.0 ? (b - a) / span : 1.0;
      if (f <= 0.0) continue;
      m.steps.push_back({a, b, f * it->a, f * it->b});
    }
    w.last = m.steps.size();
    if (w.last == w.first) continue;
    w.t0 = r.t1;
    w.t1 = r.t2;
    w.reference = r.delta;
    fill_covariates(m, w);
    m.windows.push_back(w);
  }
  return m;
}

// Windows of up to `duration` seconds of consecutive steps the reference (truth or compass)
// covers, without a gap over `max_gap`.
std::vector<MotionWindow> timed_windows(const MotionData& m, const WindowOptions& options) {
  std::vector<MotionWindow> windows;
  auto covered = [&](double t) {
    if (m.reference == ReferenceKind::kTruePose) return interpolate_truth(m.truth, t).has_value();
    return interpolate_compass(m.compass, t).has_value();
  };
  std::size_t i = 0;
  while (i < m.steps.size()) {
    if (!covered(m.steps[i].t0)) {
      ++i;
      continue;
    }
    MotionWindow w;
    w.first = i;
    w.t0 = m.steps[i].t0;
    std::size_t j = i;
    while (j < m.steps.size() && m.steps[j].t1 - w.t0 <= options.duration + 1e-9 &&
           m.steps[j].t1 - m.steps[j].t0 <= options.max_gap && covered(m.steps[j].t1)) {
      ++j;
    }
    if (j == i) {
      i = i + 1;
      continue;
    }
    w.last = j;
    w.t1 = m.steps[j - 1].t1;
    if (m.reference == ReferenceKind::kTruePose) {
      const Pose2 p = *interpolate_truth(m.truth, w.t0);
      w.heading = p.theta;
      w.x = p.x;
      w.y = p.y;
    } else {
      w.heading = *interpolate_compass(m.compass, w.t0);
    }
    fill_covariates(m, w);
    windows.push_back(w);
    i = j;
  }
  return windows;
}

template <class Records>
double median_interval(const Records& r) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < r.size(); ++i) dt.push_back(r[i].t - r[i - 1].t);
  if (dt.empty()) return 0.0;
  std::nth_element(dt.begin(), dt.begin() + static_cast<long>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

}  // namespace

MotionData build_motion_data(const Log& log, const WindowOptions& options) {
  ++motion_data_calls;
  const std::string file = log.source.empty() ? log.name : log.source;
  MotionData m = odometry_of(log, file);
  m.steps = merge_short_steps(std::move(m.steps), options);
  for (const auto& s : m.steps) {
    if (!(s.t1 >= s.t0)) {
      throw InputError(file, 0, fmt::format("odometry timestamps go backwards at t = {}", s.t1));
    }
  }
  m.compass = log.compass;
  m.compass_step = declared_compass_step(log, file);
  m.reference = reference_of(log, file);
  if (m.reference == ReferenceKind::kTruePose) m.truth = log.truth;
  if (m.reference == ReferenceKind::kRelations) {
    m = relation_windows(std::move(m), log.relations);
  } else {
    m.windows = timed_windows(m, options);
  }
  if (m.reference == ReferenceKind::kTruePose) m.reference_interval = median_interval(m.truth);
  if (m.reference == ReferenceKind::kCompass) m.reference_interval = median_interval(m.compass);
  if (m.windows.size() < options.min_windows) {
    throw InputError(file, 0,
                     fmt::format("too short a log: {} windows of {} s where the odometry and the "
                                 "reference overlap, at least {} needed",
                                 m.windows.size(), options.duration, options.min_windows));
  }
  check_motion_and_scale(m, file);
  return m;
}

}  // namespace locbench::diagnosis
