#include "core/trajectory.h"

#include <algorithm>
#include <stdexcept>

namespace locbench {

Trajectory::Trajectory(std::vector<StampedPose> poses) : poses_(std::move(poses)) {
  for (std::size_t i = 1; i < poses_.size(); ++i) {
    if (poses_[i].t < poses_[i - 1].t) {
      throw std::invalid_argument("Trajectory: timestamps go backwards");
    }
  }
}

void Trajectory::push_back(const StampedPose& p) {
  if (!poses_.empty() && p.t < poses_.back().t) {
    throw std::invalid_argument("Trajectory: timestamps go backwards");
  }
  poses_.push_back(p);
}

std::optional<Pose2> Trajectory::pose_at(double t) const {
  if (poses_.empty() || t < poses_.front().t || t > poses_.back().t) return std::nullopt;
  const auto it =
      std::lower_bound(poses_.begin(), poses_.end(), t, [](const StampedPose& p, double v) { return p.t < v; });
  if (it->t == t || it == poses_.begin()) return it->pose;
  const StampedPose& a = *(it - 1);
  const StampedPose& b = *it;
  const double s = (t - a.t) / (b.t - a.t);
  return Pose2{a.pose.x + s * (b.pose.x - a.pose.x), a.pose.y + s * (b.pose.y - a.pose.y),
               a.pose.theta + s * angle_diff(b.pose.theta, a.pose.theta)};
}

double Trajectory::path_length() const {
  double d = 0.0;
  for (std::size_t i = 1; i < poses_.size(); ++i) {
    d += translation_distance(poses_[i - 1].pose, poses_[i].pose);
  }
  return d;
}

}  // namespace locbench
