#include "algorithms/laser/scan_points.h"

#include <algorithm>
#include <cmath>

namespace locbench::laser {

namespace {

// A pose's rotation and translation, computed once for all the points it maps.
struct PointTransform {
  explicit PointTransform(const Pose2& p)
      : c(std::cos(p.theta)), s(std::sin(p.theta)), t(p.x, p.y) {}
  Eigen::Vector2d operator()(const Eigen::Vector2d& q) const {
    return {t.x() + c * q.x() - s * q.y(), t.y() + s * q.x() + c * q.y()};
  }
  double c, s;
  Eigen::Vector2d t;
};

}  // namespace

std::vector<ScanPoint> scan_points(const Scan& scan, const Pose2& robot_pose) {
  std::vector<ScanPoint> out;
  out.reserve(scan.ranges.size());
  const PointTransform mount(scan.sensor_pose), pose(robot_pose);
  const std::size_t n = std::min(scan.ranges.size(), scan.bearings.size());
  // Evenly spaced bearings (every laser scanner's): cos/sin of bearing i by rotating those of
  // bearing i − 1 by the step, re-anchored on std::cos/std::sin every 16 beams (error < 1e-14);
  // the trigonometry is otherwise half the cost of a whole EAP match.
  const double step = n > 1 ? scan.bearings[1] - scan.bearings[0] : 0.0;
  bool even = n > 1;
  for (std::size_t i = 2; even && i < n; ++i) {
    even = std::abs(scan.bearings[i] - scan.bearings[i - 1] - step) < 1e-12;
  }
  const double cs = std::cos(step), ss = std::sin(step);
  double c = 0.0, sn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!even || i % 16 == 0) {
      c = std::cos(scan.bearings[i]);
      sn = std::sin(scan.bearings[i]);
    } else {
      const double c1 = c * cs - sn * ss;
      sn = sn * cs + c * ss;
      c = c1;
    }
    if (!scan.valid(i)) continue;
    ScanPoint p;
    p.beam = i;
    p.range = scan.ranges[i];
    p.bearing = scan.bearings[i];
    p.robot = mount(Eigen::Vector2d(p.range * c, p.range * sn));  // eq. 5.2
    p.world = pose(p.robot);                                      // eq. 5.3
    out.push_back(p);
  }
  return out;
}

}  // namespace locbench::laser
