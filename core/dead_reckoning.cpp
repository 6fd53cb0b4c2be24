#include "core/dead_reckoning.h"

#include <cmath>

#include "core/diff_drive_odometry.h"

namespace locbench {

Trajectory dead_reckon_encoders(std::span<const EncoderReading> encoders, const NominalModel& model,
                                const Pose2& start) {
  Trajectory traj;
  if (encoders.empty()) return traj;
  Pose2 pose = start;
  traj.push_back({encoders[0].t, pose});
  for (std::size_t i = 1; i < encoders.size(); ++i) {
    const WheelDisplacement u = displacement_from_ticks(model, encoders[i].left - encoders[i - 1].left,
                                                        encoders[i].right - encoders[i - 1].right);
    pose = odometry_step(pose, u, model.wheelbase);
    traj.push_back({encoders[i].t, pose});
  }
  return traj;
}

Trajectory dead_reckon_velocities(std::span<const OdometryReading> odometry, const Pose2& start) {
  Trajectory traj;
  if (odometry.empty()) return traj;
  Pose2 pose = start;
  traj.push_back({odometry[0].t, pose});
  for (std::size_t i = 1; i < odometry.size(); ++i) {
    const double dt = odometry[i].t - odometry[i - 1].t;
    const double d = odometry[i - 1].tv * dt;
    const double dth = odometry[i - 1].rv * dt;
    const double mid = pose.theta + 0.5 * dth;
    pose = Pose2{pose.x + d * std::cos(mid), pose.y + d * std::sin(mid), pose.theta + dth};
    traj.push_back({odometry[i].t, pose});
  }
  return traj;
}

}  // namespace locbench
