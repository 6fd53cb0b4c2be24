#pragma once
// A scan's valid beams as points: in the robot frame (eq. 5.2, through the sensor mount) and in
// the world frame under a pose estimate (eq. 5.3). Every matcher and extractor starts here.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "algorithms/core/pose2.h"
#include "algorithms/core/scan.h"

namespace locbench::laser {

struct ScanPoint {
  std::size_t beam = 0;    // index into Scan::ranges
  double range = 0.0;      // [m]
  double bearing = 0.0;    // [rad], sensor frame
  Eigen::Vector2d robot;   // robot frame (eq. 5.2)
  Eigen::Vector2d world;   // world frame under the pose estimate (eq. 5.3)
};

// The valid beams (Scan::valid) in beam order.
std::vector<ScanPoint> scan_points(const Scan& scan, const Pose2& robot_pose);

}  // namespace locbench::laser
