#pragma once
// One laser scan: ranges at bearings in the sensor frame, the time it was taken and where the
// sensor sits on the robot.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "core/pose2.h"

namespace locbench {

struct Scan {
  double timestamp = 0.0;        // [s]
  std::vector<double> ranges;    // [m]; a range ≥ max_range means "no return"
  std::vector<double> bearings;  // [rad], sensor frame, counter-clockwise
  Pose2 sensor_pose;             // sensor in the robot frame
  double max_range = std::numeric_limits<double>::infinity();

  bool valid(std::size_t i) const { return std::isfinite(ranges[i]) && ranges[i] > 0.0 && ranges[i] < max_range; }
  // Beam i's end point in the sensor frame (eq. 5.2 before the mounting transform).
  Eigen::Vector2d point(std::size_t i) const {
    return {ranges[i] * std::cos(bearings[i]), ranges[i] * std::sin(bearings[i])};
  }
};

// Evenly spaced bearings: `count` beams from `first` to `last` inclusive.
std::vector<double> even_bearings(std::size_t count, double first, double last);

}  // namespace locbench
