#include "algorithms/laser/scan_points.h"

#include <algorithm>
#include <cmath>

namespace locbench::laser {

std::vector<ScanPoint> scan_points(const Scan& scan, const Pose2& robot_pose) {
  std::vector<ScanPoint> out;
  out.reserve(scan.ranges.size());
  const PointTransform mount(scan.sensor_pose), pose(robot_pose);
  const std::size_t n = std::min(scan.ranges.size(), scan.bearings.size());
  // The trigonometry is otherwise half the cost of a whole EAP match (BearingTrig).
  BearingTrig trig(scan.bearings, n);
  for (std::size_t i = 0; i < n; ++i) {
    trig.next(i);
    const double c = trig.c, sn = trig.s;
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
