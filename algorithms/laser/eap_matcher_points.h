#pragma once
// The scan as the EAP matcher reads it: the valid beams' world (5.3) and robot (5.2)
// coordinates in flat arrays, computed with scan_points' arithmetic (PointTransform,
// BearingTrig) so that every ScanPoint built from them equals scan_points' bit for bit, and
// the bearings' cos/sin cached per scan geometry.
#include <Eigen/Core>
#include <cstddef>
#include <cstring>
#include <vector>

#include "algorithms/laser/scan_points.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::laser::detail {

// cos/sin of a scan geometry's bearings (BearingTrig, so bit-equal to scan_points), recomputed
// only when the bearings change: a log's scans all share one geometry.
class BearingCache {
 public:
  void update(const std::vector<double>& bearings) {
    const std::size_t n = bearings.size();
    if (valid_ && n == bearings_.size() &&
        (n == 0 || std::memcmp(bearings.data(), bearings_.data(), n * sizeof(double)) == 0)) {
      return;
    }
    bearings_ = bearings;
    c_.resize(n);
    s_.resize(n);
    BearingTrig trig(bearings_, n);
    for (std::size_t i = 0; i < n; ++i) {
      trig.next(i);
      c_[i] = trig.c;
      s_[i] = trig.s;
    }
    valid_ = true;
  }
  double c(std::size_t i) const { return c_[i]; }
  double s(std::size_t i) const { return s_[i]; }

 private:
  bool valid_ = false;
  std::vector<double> bearings_, c_, s_;
};

// The scan's valid beams as flat arrays: world (5.3) and robot (5.2) coordinates computed with
// scan_points' arithmetic, so every ScanPoint built from them equals scan_points' bit for bit.
struct FlatPoints {
  std::vector<double> x, y;    // world frame under the estimate
  std::vector<double> rx, ry;  // robot frame
  std::vector<std::size_t> beam;

  void assign(const Scan& scan, const Pose2& estimate, const BearingCache& trig) {
    const PointTransform mount(scan.sensor_pose), pose(estimate);
    const std::size_t n = scan.ranges.size();
    for (auto* v : {&x, &y, &rx, &ry}) v->resize(n);
    beam.resize(n);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!scan.valid(i)) continue;
      const double r = scan.ranges[i];
      const Eigen::Vector2d robot = mount(Eigen::Vector2d(r * trig.c(i), r * trig.s(i)));
      const Eigen::Vector2d world = pose(robot);
      x[k] = world.x();
      y[k] = world.y();
      rx[k] = robot.x();
      ry[k] = robot.y();
      beam[k] = i;
      ++k;
    }
    for (auto* v : {&x, &y, &rx, &ry}) v->resize(k);
    beam.resize(k);
  }
  std::size_t size() const { return x.size(); }
  ScanPoint point(std::size_t i, const Scan& scan) const {
    ScanPoint p;
    p.beam = beam[i];
    p.range = scan.ranges[beam[i]];
    p.bearing = scan.bearings[beam[i]];
    p.robot = {rx[i], ry[i]};
    p.world = {x[i], y[i]};
    return p;
  }
};

}  // namespace locbench::laser::detail
