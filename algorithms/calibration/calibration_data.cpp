#include "algorithms/calibration/calibration_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/trajectory.h"

namespace locbench::calibration {
namespace {

// A time-stamped odometry increment and its nominal (ΔD, Δθ), for cutting intervals.
struct TimedIncrement {
  double t0 = 0.0, t1 = 0.0;
  OdometryIncrement inc;
  double nominal_distance = 0.0;
  double nominal_rotation = 0.0;
};

// Ground truth as a trajectory plus its record times (for gap checks).
struct Reference {
  Trajectory trajectory;
  std::vector<double> times;

  // True when [t0, t1] lies inside the records and no two consecutive records around it are
  // further apart than `max_gap`.
  bool covers(double t0, double t1, double max_gap) const {
    if (times.empty() || t0 < times.front() || t1 > times.back()) return false;
    auto it = std::upper_bound(times.begin(), times.end(), t0);
    if (it != times.begin()) --it;
    for (; it + 1 != times.end() && *it < t1; ++it) {
      if (*(it + 1) - *it > max_gap) return false;
    }
    return true;
  }
};

Reference truth_reference(const Log& log) {
  std::vector<StampedPose> poses;
  Reference r;
  for (const TruePose& p : log.truth) {
    poses.push_back({p.t, p.pose});
    r.times.push_back(p.t);
  }
  try {
    r.trajectory = Trajectory(std::move(poses));
  } catch (const std::invalid_argument& e) {
    throw InputError(log.source, 0, std::string("ground truth: ") + e.what());
  }
  return r;
}

// Cuts increments into samples (SampleIntervalOptions) whose reference comes from `truth`.
std::vector<CalibrationSample> cut_samples(const std::vector<TimedIncrement>& incs, const SampleIntervalOptions& opt,
                                           const Reference& truth, const std::optional<Pose2>& sensor_mount) {
  std::vector<CalibrationSample> out;
  std::size_t i = 0;
  while (i < incs.size()) {
    CalibrationSample s;
    double dist = 0.0, rot = 0.0;
    bool moved = false;
    const double t0 = incs[i].t0;
    for (; i < incs.size(); ++i) {
      const TimedIncrement& k = incs[i];
      s.increments.push_back(k.inc);
      dist += std::abs(k.nominal_distance);
      rot += std::abs(k.nominal_rotation);
      moved = moved || k.inc.first != 0.0 || k.inc.second != 0.0;
      if (dist >= opt.max_distance || rot >= opt.max_rotation || k.t1 - t0 >= opt.max_duration) {
        ++i;
        break;
      }
    }
    const double t1 = incs[i - 1].t1;
    if (opt.skip_stationary && !moved) continue;
    if (!truth.covers(t0, t1, opt.max_reference_gap)) continue;
    const auto a = truth.trajectory.pose_at(t0);
    const auto b = truth.trajectory.pose_at(t1);
    if (!a || !b) continue;
    s.reference = sensor_mount ? between(*a * *sensor_mount, *b * *sensor_mount) : between(*a, *b);
    s.t_start = t0;
    s.t_end = t1;
    out.push_back(std::move(s));
  }
  return out;
}

double param_or(const Log& log, const char* name, double fallback) {
  const auto it = log.params.find(name);
  if (it == log.params.end()) return fallback;
  try {
    return std::stod(it->second);
  } catch (const std::exception&) {
    return fallback;
  }
}

// The odometry poses of a log: ODOM records, else the odometry poses logged with the scans.
Trajectory odometry_poses(const Log& log) {
  std::vector<StampedPose> poses;
  if (!log.odometry.empty()) {
    for (const OdometryReading& o : log.odometry) poses.push_back({o.t, o.pose});
  } else {
    for (const LaserReading& l : log.laser) poses.push_back({l.scan.timestamp, l.odom_pose});
  }
  try {
    return Trajectory(std::move(poses));
  } catch (const std::invalid_argument& e) {
    throw InputError(log.source, 0, std::string("odometry: ") + e.what());
  }
}

}  // namespace

OdometryIncrement arc_increment(const Pose2& delta, double dt) {
  const double chord = std::hypot(delta.x, delta.y);
  if (chord == 0.0) return {0.0, delta.theta, dt};
  const double half = 0.5 * delta.theta;
  const double length = std::abs(half) < 1e-9 ? chord : chord * half / std::sin(half);
  const double forward = delta.x * std::cos(half) + delta.y * std::sin(half);
  return {forward >= 0.0 ? length : -length, delta.theta, dt};
}

CalibrationData calibration_data_from_encoders(const Log& log, const SampleIntervalOptions& intervals,
                                               std::optional<NominalModel> nominal, std::optional<Pose2> sensor_mount) {
  if (log.encoders.size() < 2) throw InputError(log.source, 0, "needs ENCODER records");
  if (log.truth.empty()) throw InputError(log.source, 0, "needs TRUEPOS ground truth");
  if (!nominal) nominal = log.nominal_model();
  if (!nominal) {
    throw InputError(log.source, 0,
                     "no nominal odometry model (PARAM robot_meters_per_tick_left, "
                     "robot_meters_per_tick_right, robot_wheelbase)");
  }
  // A NaN, zero, negative or denormal geometry is an input error, not a fit.
  const auto plausible = [&](double v, const char* name, double lo, double hi, const char* unit) {
    if (!(v >= lo && v <= hi)) {
      throw InputError(log.source, 0, fmt::format("PARAM {} = {}: expected {} in [{}, {}]", name, v, unit, lo, hi));
    }
  };
  plausible(nominal->wheelbase, "robot_wheelbase", 0.01, 5.0, "metres");
  plausible(nominal->meters_per_tick_left, "robot_meters_per_tick_left", 1e-9, 0.1, "metres per tick");
  plausible(nominal->meters_per_tick_right, "robot_meters_per_tick_right", 1e-9, 0.1, "metres per tick");
  if (!(log.encoders.back().t > log.encoders.front().t)) {
    throw InputError(log.source, 0, "ENCODER records all have the same time: expected increasing timestamps");
  }
  const Reference truth = truth_reference(log);
  std::vector<TimedIncrement> incs;
  for (std::size_t k = 0; k + 1 < log.encoders.size(); ++k) {
    const EncoderReading &a = log.encoders[k], &b = log.encoders[k + 1];
    if (b.t < a.t) throw InputError(log.source, 0, "ENCODER times go back");
    TimedIncrement t;
    t.t0 = a.t + intervals.odometry_time_offset;
    t.t1 = b.t + intervals.odometry_time_offset;
    std::int64_t dl = 0, dr = 0;
    if (__builtin_sub_overflow(b.left, a.left, &dl) || __builtin_sub_overflow(b.right, a.right, &dr)) {
      throw InputError(log.source, 0,
                       fmt::format("ENCODER at t = {}: the tick counts jump by more than the 64-bit range", b.t));
    }
    t.inc = {static_cast<double>(dl), static_cast<double>(dr), b.t - a.t};
    const double ul = nominal->meters_per_tick_left * t.inc.first;
    const double ur = nominal->meters_per_tick_right * t.inc.second;
    t.nominal_distance = 0.5 * (ul + ur);
    t.nominal_rotation = (ur - ul) / nominal->wheelbase;
    incs.push_back(t);
  }
  CalibrationData d;
  d.source = log.source.empty() ? log.name : log.source;
  d.kind = OdometryInputKind::kWheelTicks;
  d.meters_per_tick_left = nominal->meters_per_tick_left;
  d.meters_per_tick_right = nominal->meters_per_tick_right;
  d.quantized_ticks = true;
  d.nominal = Eigen::Vector3d(1.0, 1.0, nominal->wheelbase);
  d.sensor_reference = sensor_mount.has_value();
  d.nominal_sensor_pose =
      Pose2(param_or(log, "robot_frontlaser_offset", 0.0), param_or(log, "robot_frontlaser_side_offset", 0.0),
            param_or(log, "robot_frontlaser_angular_offset", 0.0));
  d.samples = cut_samples(incs, intervals, truth, sensor_mount);
  if (d.samples.empty()) throw InputError(log.source, 0, "no sample lies inside the ground truth");
  return d;
}

CalibrationData calibration_data_from_relations(const Log& log, const RelationSampleOptions& options) {
  if (log.relations.empty()) throw InputError(log.source, 0, "needs reference relations");
  if (log.odometry.empty() && log.laser.empty()) {
    throw InputError(log.source, 0, "needs ODOM records (or odometry poses in FLASER records)");
  }
  const Trajectory odom = odometry_poses(log);
  std::vector<double> times;
  for (const StampedPose& p : odom.poses()) times.push_back(p.t);
  CalibrationData d;
  d.source = log.source.empty() ? log.name : log.source;
  d.kind = OdometryInputKind::kBodyIncrements;
  d.nominal = Eigen::Vector3d(1.0, 1.0, 0.0);
  for (const Relation& r : log.relations) {
    double t1 = r.t1, t2 = r.t2;
    Pose2 ref = r.delta;
    if (t2 < t1) {
      std::swap(t1, t2);
      ref = ref.inverse();
    }
    if (t2 - t1 > options.max_duration) continue;
    const auto a = odom.pose_at(t1);
    const auto b = odom.pose_at(t2);
    if (!a || !b) continue;
    CalibrationSample s;
    s.reference = ref;
    s.t_start = t1;
    s.t_end = t2;
    Pose2 prev = *a;
    double tprev = t1;
    auto it = std::upper_bound(times.begin(), times.end(), t1);
    for (; it != times.end() && *it < t2; ++it) {
      const Pose2& p = odom.poses()[static_cast<std::size_t>(it - times.begin())].pose;
      s.increments.push_back(arc_increment(between(prev, p), *it - tprev));
      prev = p;
      tprev = *it;
    }
    s.increments.push_back(arc_increment(between(prev, *b), t2 - tprev));
    d.samples.push_back(std::move(s));
  }
  if (d.samples.empty()) {
    throw InputError(log.source, 0, "no relation lies inside the odometry's time span");
  }
  std::stable_sort(d.samples.begin(), d.samples.end(),
                   [](const CalibrationSample& a, const CalibrationSample& b) { return a.t_start < b.t_start; });
  return d;
}

CalibrationData calibration_data_from_velocities(const Log& log, const SampleIntervalOptions& intervals) {
  if (log.odometry.size() < 2) throw InputError(log.source, 0, "needs ODOM velocity records");
  if (log.truth.empty()) throw InputError(log.source, 0, "needs ground truth");
  const Reference truth = truth_reference(log);
  std::vector<TimedIncrement> incs;
  for (std::size_t k = 0; k + 1 < log.odometry.size(); ++k) {
    const OdometryReading &a = log.odometry[k], &b = log.odometry[k + 1];
    if (b.t < a.t) throw InputError(log.source, 0, "ODOM times go back");
    const double dt = b.t - a.t;
    TimedIncrement t;
    t.t0 = a.t + intervals.odometry_time_offset;
    t.t1 = b.t + intervals.odometry_time_offset;
    t.inc = {a.tv * dt, a.rv * dt, dt};
    t.nominal_distance = t.inc.first;
    t.nominal_rotation = t.inc.second;
    incs.push_back(t);
  }
  CalibrationData d;
  d.source = log.source.empty() ? log.name : log.source;
  d.kind = OdometryInputKind::kVelocityIntegrals;
  d.nominal = Eigen::Vector3d(1.0, 1.0, 0.0);
  d.samples = cut_samples(incs, intervals, truth, std::nullopt);
  if (d.samples.empty()) throw InputError(log.source, 0, "no sample lies inside the ground truth");
  return d;
}

CalibrationData calibration_data_from_wheel_speed_tuples(std::span<const WheelSpeedTuple> tuples, double nominal_radius,
                                                         double nominal_axle) {
  CalibrationData d;
  d.source = "wheel-speed tuples";
  d.kind = OdometryInputKind::kWheelAngles;
  d.nominal = Eigen::Vector3d(nominal_radius, nominal_radius, nominal_axle);
  d.sensor_reference = true;
  for (const WheelSpeedTuple& t : tuples) {
    CalibrationSample s;
    s.increments.push_back({t.T * t.phi_l, t.T * t.phi_r, t.T});
    s.reference = t.sm;
    d.samples.push_back(std::move(s));
  }
  return d;
}

CalibrationData calibration_data_from_motion_pairs(std::span<const RelativeMotionPair> pairs) {
  CalibrationData d;
  d.source = "relative-motion pairs";
  d.kind = OdometryInputKind::kBodyIncrements;
  d.nominal = Eigen::Vector3d(1.0, 1.0, 0.0);
  for (const RelativeMotionPair& p : pairs) {
    CalibrationSample s;
    s.increments.push_back(arc_increment(p.odometry));
    s.reference = p.reference;
    d.samples.push_back(std::move(s));
  }
  return d;
}

CalibrationData calibration_data_from_tick_motions(std::span<const TickMotion> rows, const NominalModel& nominal) {
  CalibrationData d;
  d.source = "tick motions";
  d.kind = OdometryInputKind::kWheelTicks;
  d.meters_per_tick_left = nominal.meters_per_tick_left;
  d.meters_per_tick_right = nominal.meters_per_tick_right;
  d.nominal = Eigen::Vector3d(1.0, 1.0, nominal.wheelbase);
  for (const TickMotion& r : rows) {
    CalibrationSample s;
    s.increments.push_back({r.left, r.right, 0.0});
    s.reference = r.reference;
    d.samples.push_back(std::move(s));
  }
  return d;
}

CalibrationData subset(const CalibrationData& data, std::size_t begin, std::size_t end) {
  CalibrationData d;
  d.source = data.source;
  d.kind = data.kind;
  d.meters_per_tick_left = data.meters_per_tick_left;
  d.meters_per_tick_right = data.meters_per_tick_right;
  d.quantized_ticks = data.quantized_ticks;
  d.nominal = data.nominal;
  d.sensor_reference = data.sensor_reference;
  d.nominal_sensor_pose = data.nominal_sensor_pose;
  end = std::min(end, data.samples.size());
  begin = std::min(begin, end);
  d.samples.assign(data.samples.begin() + static_cast<std::ptrdiff_t>(begin),
                   data.samples.begin() + static_cast<std::ptrdiff_t>(end));
  return d;
}

bool is_finite(const CalibrationSample& s) {
  if (!std::isfinite(s.reference.x) || !std::isfinite(s.reference.y) || !std::isfinite(s.reference.theta)) {
    return false;
  }
  return std::all_of(s.increments.begin(), s.increments.end(), [](const OdometryIncrement& i) {
    return std::isfinite(i.first) && std::isfinite(i.second) && std::isfinite(i.dt);
  });
}

CalibrationData calibration_data_from_records(const CalibrationRecords& records) {
  CalibrationData d;
  if (!records.wheel_speed_tuples.empty()) {
    d = calibration_data_from_wheel_speed_tuples(records.wheel_speed_tuples);
  } else if (!records.tick_motions.empty()) {
    d = calibration_data_from_tick_motions(records.tick_motions);
  } else {
    d = calibration_data_from_motion_pairs(records.motion_pairs);
  }
  d.source = records.source;
  if (d.samples.empty()) throw InputError(d.source, 0, "no samples");
  return d;
}

}  // namespace locbench::calibration
