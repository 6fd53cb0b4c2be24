#pragma once
// Scans for the laser-baseline tests: an LMS 200-like scanner (181 beams over −90°…90°, 8 m)
// ray-cast against a hand-made LineMap, and the truth the tests compare with, also from ray
// casting (never written down by hand).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <set>
#include <vector>

#include "algorithms/laser/scan_points.h"
#include "core/angle.h"
#include "core/line_map.h"
#include "core/rng.h"
#include "core/scan.h"
#include "datasets/sim/laser_model.h"

namespace locbench::baselines::laser::test {

inline Scan lms_scan(const LineMap& world, const Pose2& pose, double sigma = 0.0, std::uint64_t seed = 1,
                     int beams = 181) {
  sim::LaserConfig c;
  c.beams = beams;
  c.noise = sigma;
  sim::LaserModel model(c, world, Rng(seed));
  return model.measure(pose, 0.0);
}

// A map of the given segments {x1, y1, x2, y2}.
inline LineMap segments_map(std::initializer_list<std::array<double, 4>> rows) {
  LineMap m;
  for (const auto& r : rows) m.segments.push_back({{r[0], r[1]}, {r[2], r[3]}});
  return m;
}

// The segment each beam of `scan` truly hits from `pose` (or -1).
inline std::vector<int> true_segment_of_beams(const LineMap& map, const Pose2& pose, const Scan& scan) {
  const Pose2 sensor = pose * scan.sensor_pose;
  std::vector<int> seg(scan.bearings.size(), -1);
  for (std::size_t i = 0; i < seg.size(); ++i) {
    if (auto hit = map.ray_cast(sensor.translation(), sensor.theta + scan.bearings[i], scan.max_range)) {
      seg[i] = static_cast<int>(hit->segment);
    }
  }
  return seg;
}

// Segments seen by at least `min_points` consecutive beams whose hits span at least
// `min_length`: what an extract-then-match pipeline with that acceptance can find.
inline std::set<std::size_t> visible_segments(const LineMap& map, const Pose2& pose, const Scan& scan,
                                              std::size_t min_points = 5, double min_length = 0.2) {
  const std::vector<int> seg = true_segment_of_beams(map, pose, scan);
  const Pose2 sensor = pose * scan.sensor_pose;
  const auto hit_point = [&](std::size_t i) {
    const auto hit = map.ray_cast(sensor.translation(), sensor.theta + scan.bearings[i], scan.max_range);
    const double a = sensor.theta + scan.bearings[i];
    return Eigen::Vector2d(sensor.x + hit->range * std::cos(a), sensor.y + hit->range * std::sin(a));
  };
  std::set<std::size_t> visible;
  for (std::size_t b = 0; b < seg.size();) {
    std::size_t e = b + 1;
    while (e < seg.size() && seg[e] == seg[b]) ++e;
    if (seg[b] >= 0 && e - b >= min_points && (hit_point(e - 1) - hit_point(b)).norm() >= min_length) {
      visible.insert(static_cast<std::size_t>(seg[b]));
    }
    b = e;
  }
  return visible;
}

struct LineError {
  double rho = 0.0;   // [m]
  double beta = 0.0;  // [rad]
};
// |Δρ|, |Δβ| between two normal forms, allowing (ρ, β) ≡ (−ρ, β + π) for lines through the
// origin (ρ ≈ 0, where the sign of the normal is arbitrary).
inline LineError line_error(const LineParams& a, const LineParams& b) {
  const LineError same{std::abs(a.rho - b.rho), std::abs(angle_diff(a.beta, b.beta))};
  const LineError flipped{std::abs(a.rho + b.rho), std::abs(angle_diff(a.beta, b.beta + kPi))};
  return same.beta <= flipped.beta ? same : flipped;
}

// The line (ρ, β) of frame-A coordinates expressed in frame B, where `a_in_b` maps A to B.
inline LineParams transform_line(const LineParams& l, const Pose2& a_in_b) {
  const Eigen::Vector2d n(std::cos(l.beta), std::sin(l.beta));
  const Eigen::Vector2d foot = a_in_b * Eigen::Vector2d(l.rho * n);
  const double beta = l.beta + a_in_b.theta;
  const Eigen::Vector2d nb(std::cos(beta), std::sin(beta));
  const double rho = nb.dot(foot);
  return rho >= 0.0 ? LineParams{rho, wrap_angle(beta)} : LineParams{-rho, wrap_angle(beta + kPi)};
}

}  // namespace locbench::baselines::laser::test
