#pragma once
// A scan's valid beams as points: in the robot frame (eq. 5.2, through the sensor mount) and in
// the world frame under a pose estimate (eq. 5.3). Every matcher and extractor starts here.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::laser {

struct ScanPoint {
  std::size_t beam = 0;   // index into Scan::ranges
  double range = 0.0;     // [m]
  double bearing = 0.0;   // [rad], sensor frame
  Eigen::Vector2d robot;  // robot frame (eq. 5.2)
  Eigen::Vector2d world;  // world frame under the pose estimate (eq. 5.3)
};

// The valid beams (Scan::valid) in beam order.
std::vector<ScanPoint> scan_points(const Scan& scan, const Pose2& robot_pose);

// A pose's rotation and translation, computed once for all the points it maps (eq. 5.2–5.3).
struct PointTransform {
  explicit PointTransform(const Pose2& p) : c(std::cos(p.theta)), s(std::sin(p.theta)), t(p.x, p.y) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& q) const {
    return {t.x() + c * q.x() - s * q.y(), t.y() + s * q.x() + c * q.y()};
  }
  double c, s;
  Eigen::Vector2d t;
};

// cos and sin of the first n bearings, in beam order, exactly as scan_points computes them.
// Evenly spaced bearings (every laser scanner's): those of bearing i by rotating those of
// bearing i − 1 by the step, re-anchored on std::cos/std::sin every 16 beams (error < 1e-14);
// otherwise std::cos/std::sin of each. Call next() for i = 0, 1, …, n − 1 in order.
class BearingTrig {
 public:
  BearingTrig(const std::vector<double>& bearings, std::size_t n) : bearings_(bearings) {
    const double step = n > 1 ? bearings[1] - bearings[0] : 0.0;
    even_ = n > 1;
    for (std::size_t i = 2; even_ && i < n; ++i) {
      even_ = std::abs(bearings[i] - bearings[i - 1] - step) < 1e-12;
    }
    cs_ = std::cos(step);
    ss_ = std::sin(step);
  }
  void next(std::size_t i) {
    if (!even_ || i % 16 == 0) {
      c = std::cos(bearings_[i]);
      s = std::sin(bearings_[i]);
    } else {
      const double c1 = c * cs_ - s * ss_;
      s = s * cs_ + c * ss_;
      c = c1;
    }
  }
  double c = 0.0, s = 0.0;  // cos and sin of bearing i after next(i)

 private:
  const std::vector<double>& bearings_;
  bool even_ = false;
  double cs_ = 1.0, ss_ = 0.0;
};

}  // namespace locbench::laser
