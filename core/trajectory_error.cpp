#include "core/trajectory_error.h"

#include <cmath>

#include "core/statistics.h"

namespace locbench {

ErrorStatistics error_statistics(std::span<const double> errors) {
  ErrorStatistics s;
  s.n = errors.size();
  if (errors.empty()) return s;
  for (double e : errors) s.sse += e * e;
  s.rmse = std::sqrt(s.sse / static_cast<double>(s.n));
  s.mean = mean(errors);
  s.median = quantile(errors, 0.5);
  s.std = std::sqrt(central_moment(errors, 2));  // population std, as evo reports
  s.min = quantile(errors, 0.0);
  s.max = quantile(errors, 1.0);
  return s;
}

PoseErrors absolute_pose_error(const Trajectory& reference, const Trajectory& estimate, Alignment alignment) {
  PoseErrors out;
  if (reference.empty() || estimate.empty()) return out;
  Pose2 correction = Pose2::identity();  // applied on the left of each estimate pose
  if (alignment == Alignment::kFirstPose) {
    const auto ref0 = reference.pose_at(estimate.start_time());
    if (!ref0) return out;
    correction = *ref0 * estimate.poses().front().pose.inverse();
  }
  for (const StampedPose& p : estimate.poses()) {
    const auto ref = reference.pose_at(p.t);
    if (!ref) continue;
    const Pose2 e = between(*ref, correction * p.pose);
    out.t.push_back(p.t);
    out.translation.push_back(std::hypot(e.x, e.y));
    out.rotation.push_back(std::abs(e.theta));
  }
  return out;
}

PoseErrors relation_error(const Trajectory& estimate, std::span<const Relation> relations) {
  PoseErrors out;
  for (const Relation& r : relations) {
    const auto a = estimate.pose_at(r.t1);
    const auto b = estimate.pose_at(r.t2);
    if (!a || !b) continue;
    const Pose2 e = between(r.delta, between(*a, *b));
    out.t.push_back(r.t1);
    out.translation.push_back(std::hypot(e.x, e.y));
    out.rotation.push_back(std::abs(e.theta));
  }
  return out;
}

std::vector<Relation> window_relations(const Trajectory& reference, double window) {
  std::vector<Relation> out;
  if (reference.empty() || !(window > 0.0)) return out;
  for (double t = reference.start_time(); t + window <= reference.end_time(); t += window) {
    const auto a = reference.pose_at(t);
    const auto b = reference.pose_at(t + window);
    if (a && b) out.push_back({t, t + window, between(*a, *b)});
  }
  return out;
}

}  // namespace locbench
