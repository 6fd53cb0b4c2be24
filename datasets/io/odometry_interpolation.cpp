#include "datasets/io/odometry_interpolation.h"

#include <algorithm>
#include <vector>

namespace locbench::io {
namespace {

// Interpolates records sorted by time; time_of and pose_of read one record.
template <typename Records, typename TimeOf, typename PoseOf>
std::optional<Pose2> interpolate(const Records& records, double t, TimeOf time_of, PoseOf pose_of) {
  if (records.empty() || !(t >= time_of(records.front())) || !(t <= time_of(records.back()))) {
    return std::nullopt;
  }
  const auto it =
      std::lower_bound(records.begin(), records.end(), t, [&](const auto& r, double v) { return time_of(r) < v; });
  if (time_of(*it) == t || it == records.begin()) return pose_of(*it);
  const Pose2& a = pose_of(*(it - 1));
  const Pose2& b = pose_of(*it);
  const double ta = time_of(*(it - 1));
  const double s = (t - ta) / (time_of(*it) - ta);
  return Pose2(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.theta + s * angle_diff(b.theta, a.theta));
}

}  // namespace

Trajectory odometry_trajectory(const Log& log) {
  std::vector<StampedPose> poses;
  if (!log.odometry.empty()) {
    poses.reserve(log.odometry.size());
    for (const auto& r : log.odometry) poses.push_back({r.t, r.pose});
  } else {
    poses.reserve(log.laser.size());
    for (const auto& r : log.laser) poses.push_back({r.scan.timestamp, r.odom_pose});
  }
  return Trajectory(std::move(poses));
}

std::optional<Pose2> interpolate_odometry(const Log& log, double t) {
  if (!log.odometry.empty()) {
    return interpolate(
        log.odometry, t, [](const OdometryReading& r) { return r.t; },
        [](const OdometryReading& r) -> const Pose2& { return r.pose; });
  }
  return interpolate(
      log.laser, t, [](const LaserReading& r) { return r.scan.timestamp; },
      [](const LaserReading& r) -> const Pose2& { return r.odom_pose; });
}

std::optional<Pose2> interpolate_truth(const Log& log, double t) {
  return interpolate(
      log.truth, t, [](const TruePose& r) { return r.t; }, [](const TruePose& r) -> const Pose2& { return r.pose; });
}

}  // namespace locbench::io
