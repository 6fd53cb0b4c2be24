#pragma once
// A time-stamped sequence of poses, with interpolation in time.
#include <optional>
#include <vector>

#include "core/pose2.h"

namespace locbench {

struct StampedPose {
  double t = 0.0;
  Pose2 pose;
};

class Trajectory {
 public:
  Trajectory() = default;
  // Poses must be in non-decreasing time order (std::invalid_argument otherwise).
  explicit Trajectory(std::vector<StampedPose> poses);

  void push_back(const StampedPose& p);  // time must not go backwards
  const std::vector<StampedPose>& poses() const { return poses_; }
  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  double start_time() const { return poses_.front().t; }
  double end_time() const { return poses_.back().t; }

  // Pose at time t by linear interpolation of position and shortest-arc interpolation of
  // heading; nullopt outside [start_time, end_time].
  std::optional<Pose2> pose_at(double t) const;
  // Total distance travelled along the polyline [m].
  double path_length() const;

 private:
  std::vector<StampedPose> poses_;
};

}  // namespace locbench
