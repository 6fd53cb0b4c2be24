#pragma once
// Test scaffolding for chapter 6 (also used by tests/baselines/localization): a scan ray-cast
// from a TRUE pose, and SegmentMatches built by assigning each point to the map segment its
// beam really hit (an oracle association, standing in for the matchers), with world
// coordinates under an ESTIMATE — what a matcher would hand to the pose correction.
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "algorithms/laser/line_fit.h"
#include "algorithms/laser/scan_points.h"
#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/rng.h"
#include "core/scan.h"
#include "core/units.h"

namespace locbench::test {

struct RayCastScan {
  Scan scan;
  std::vector<std::optional<std::size_t>> hit;  // per beam: the segment really hit
};

// LMS 200-like scan (§5.4): 181 beams over −90°…90°, 8 m; Gaussian range noise σ when rng given.
inline RayCastScan ray_cast_scan(const LineMap& map, const Pose2& truth, Rng* rng = nullptr, double sigma = mm(5.0),
                                 const Pose2& mount = Pose2::identity(), std::size_t beams = 181,
                                 double max_range = 8.0) {
  RayCastScan out;
  out.scan.bearings = even_bearings(beams, -deg(90.0), deg(90.0));
  out.scan.sensor_pose = mount;
  out.scan.max_range = max_range;
  const Pose2 sensor = truth * mount;
  for (const double b : out.scan.bearings) {
    const auto h = map.ray_cast(sensor.translation(), sensor.theta + b, max_range);
    if (!h) {
      out.scan.ranges.push_back(max_range);
      out.hit.push_back(std::nullopt);
      continue;
    }
    double r = h->range;
    if (rng) r += rng->normal(0.0, sigma);
    out.scan.ranges.push_back(r);
    out.hit.push_back(h->segment);
  }
  return out;
}

// One SegmentMatch per segment hit by at least `min_points` beams, in order of first beam.
inline std::vector<laser::SegmentMatch> matches_by_true_hit(const RayCastScan& s, const Pose2& estimate,
                                                            std::size_t min_points = 5) {
  const auto points = laser::scan_points(s.scan, estimate);
  std::vector<laser::SegmentMatch> out;
  std::vector<std::size_t> order;
  for (const auto& p : points) {
    const std::size_t seg = *s.hit[p.beam];
    std::size_t k = 0;
    while (k < out.size() && out[k].map_segment != seg) ++k;
    if (k == out.size()) {
      out.push_back({});
      out.back().map_segment = seg;
    }
    out[k].points.push_back(p);
  }
  std::vector<laser::SegmentMatch> kept;
  for (auto& m : out) {
    if (m.points.size() < min_points) continue;
    std::vector<Eigen::Vector2d> w;
    for (const auto& p : m.points) w.push_back(p.world);
    m.fit = laser::fit_line(w);
    kept.push_back(std::move(m));
  }
  return kept;
}

// A match made of hand-placed robot-frame points (beam bearing from the robot centre).
inline laser::SegmentMatch hand_match(std::size_t map_segment, const std::vector<Eigen::Vector2d>& robot_points,
                                      const Pose2& estimate) {
  laser::SegmentMatch m;
  m.map_segment = map_segment;
  std::vector<Eigen::Vector2d> w;
  for (std::size_t i = 0; i < robot_points.size(); ++i) {
    laser::ScanPoint p;
    p.beam = i;
    p.robot = robot_points[i];
    p.range = robot_points[i].norm();
    p.bearing = std::atan2(robot_points[i].y(), robot_points[i].x());
    p.world = estimate * p.robot;
    w.push_back(p.world);
    m.points.push_back(p);
  }
  m.fit = laser::fit_line(w);
  return m;
}

// Robot-frame points that the true pose sees on the world segment a→b (n points evenly spaced).
inline std::vector<Eigen::Vector2d> robot_points_on(const Pose2& truth, const Eigen::Vector2d& a,
                                                    const Eigen::Vector2d& b, int n) {
  std::vector<Eigen::Vector2d> out;
  const Pose2 inv = truth.inverse();
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
    out.push_back(inv * (a + t * (b - a)));
  }
  return out;
}

}  // namespace locbench::test
