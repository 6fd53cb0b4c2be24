#include "algorithms/laser/scan_points.h"

namespace locbench::laser {

std::vector<ScanPoint> scan_points(const Scan& scan, const Pose2& robot_pose) {
  std::vector<ScanPoint> out;
  out.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!scan.valid(i)) continue;
    ScanPoint p;
    p.beam = i;
    p.range = scan.ranges[i];
    p.bearing = scan.bearings[i];
    p.robot = scan.sensor_pose * scan.point(i);  // eq. 5.2
    p.world = robot_pose * p.robot;              // eq. 5.3
    out.push_back(p);
  }
  return out;
}

}  // namespace locbench::laser
