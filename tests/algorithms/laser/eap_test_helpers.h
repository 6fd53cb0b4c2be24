#pragma once
// Scans, maps and comparisons shared by the EAP tests.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/laser/segment_match.h"
#include "core/angle.h"
#include "core/line_map.h"
#include "core/rng.h"
#include "core/scan.h"
#include "core/units.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/worlds.h"

namespace locbench::laser::test {

// The thesis's pose in the room (§5.4): (2000 mm, 1000 mm, 46°).
inline Pose2 thesis_pose() { return {2.0, 1.0, deg(46.0)}; }

// An LMS 200-like scan (181 beams, −90°…90°, 8 m) of `world` from `truth`.
inline Scan simulated_scan(const LineMap& world, const Pose2& truth, double noise = 0.0, std::uint64_t seed = 1,
                           double dropout = 0.0) {
  sim::LaserConfig c;
  c.noise = noise;
  c.dropout = dropout;
  return sim::LaserModel(c, world, Rng(seed)).measure(truth, 0.0);
}

// A scan from a sensor at the origin of the robot frame whose beams end at the given points of
// the robot frame (exactly, up to rounding); a NaN point becomes an invalid beam.
inline Scan scan_through(const std::vector<Eigen::Vector2d>& robot_points) {
  Scan s;
  s.max_range = 8.0;
  for (const Eigen::Vector2d& p : robot_points) {
    if (std::isnan(p.x())) {
      s.bearings.push_back(s.bearings.empty() ? 0.0 : s.bearings.back());
      s.ranges.push_back(s.max_range);
    } else {
      s.bearings.push_back(std::atan2(p.y(), p.x()));
      s.ranges.push_back(p.norm());
    }
  }
  return s;
}
inline Eigen::Vector2d invalid_beam() { return {std::nan(""), std::nan("")}; }

// Segments hit by the true scan, by ray casting: a segment counts as visible when some run of
// ≥ 5 consecutive beams hits it (beams that hit nothing skipped) spanning more than 0.2 m —
// the thesis's acceptance rule applied to the ground truth instead of to ω1.
inline std::set<std::size_t> visible_segments(const LineMap& world, const Pose2& truth) {
  sim::LaserConfig c;
  const auto bearings = even_bearings(static_cast<std::size_t>(c.beams), c.first_bearing, c.last_bearing);
  struct Hit {
    std::size_t segment;
    Eigen::Vector2d point;
  };
  std::vector<Hit> hits;
  for (double b : bearings) {
    const double a = truth.theta + b;
    if (const auto h = world.ray_cast(truth.translation(), a, c.max_range)) {
      hits.push_back({h->segment, truth.translation() + h->range * Eigen::Vector2d(std::cos(a), std::sin(a))});
    }
  }
  std::set<std::size_t> out;
  std::size_t begin = 0;
  while (begin < hits.size()) {
    std::size_t end = begin + 1;
    while (end < hits.size() && hits[end].segment == hits[begin].segment) ++end;
    if (end - begin >= 5 && (hits[end - 1].point - hits[begin].point).norm() > 0.2) {
      out.insert(hits[begin].segment);
    }
    begin = end;
  }
  return out;
}

// For each beam of an LMS 200-like scan from `truth`, the segment it really hits (SIZE_MAX for
// none), by ray casting.
inline std::vector<std::size_t> hit_segments(const LineMap& world, const Pose2& truth) {
  sim::LaserConfig c;
  std::vector<std::size_t> out;
  for (double b : even_bearings(static_cast<std::size_t>(c.beams), c.first_bearing, c.last_bearing)) {
    const auto h = world.ray_cast(truth.translation(), truth.theta + b, c.max_range);
    out.push_back(h ? h->segment : static_cast<std::size_t>(-1));
  }
  return out;
}

inline std::set<std::size_t> matched_segments(const MatchResult& r) {
  std::set<std::size_t> out;
  for (const auto& m : r.matches) out.insert(m.map_segment);
  return out;
}

// |Δρ| and |Δβ| between two normal-form lines, treating (ρ, β) and (−ρ, β + π) as the same line
// (β is ill-defined for a line through the origin, like the room's walls x = 0 and y = 0).
struct LineError {
  double rho = 0.0;
  double beta = 0.0;
};
inline LineError line_error(const LineParams& a, const LineParams& b) {
  double rho_b = b.rho, beta_b = b.beta;
  if (std::abs(angle_diff(a.beta, beta_b)) > kPi / 2) {
    rho_b = -rho_b;
    beta_b += kPi;
  }
  return {std::abs(a.rho - rho_b), std::abs(angle_diff(a.beta, beta_b))};
}
inline double signed_beta_error(const LineParams& a, const LineParams& b) {
  double beta_b = b.beta;
  if (std::abs(angle_diff(a.beta, beta_b)) > kPi / 2) beta_b += kPi;
  return angle_diff(a.beta, beta_b);
}

// Both claim orders, with and without removing claimed points, and the stadium region with the
// range-incidence weighting.
inline std::vector<EapOptions> claim_and_region_variants() {
  std::vector<EapOptions> v(4);
  v[1].claim_order = ClaimOrder::kMapOrder;
  v[2].remove_claimed = false;
  v[3].region = RegionRule::kStadium;
  v[3].weighting.kind = HoughWeighting::kRangeIncidence;
  return v;
}

// Checks that `a` and `b` matched the same segments in the same order with as many points each,
// then calls check(x, y) on each pair of matches.
template <class Check>
void expect_same_segments(const MatchResult& a, const MatchResult& b, const std::string& what, Check&& check) {
  ASSERT_EQ(a.matches.size(), b.matches.size()) << what;
  for (std::size_t k = 0; k < a.matches.size(); ++k) {
    const SegmentMatch& x = a.matches[k];
    const SegmentMatch& y = b.matches[k];
    ASSERT_EQ(x.map_segment, y.map_segment) << what;
    ASSERT_EQ(x.points.size(), y.points.size()) << what << ", segment " << x.map_segment;
    check(x, y);
  }
}

// `count` segments of length 0.3–3 m, uniformly placed and oriented in [0, size]².
inline LineMap random_map(std::size_t count, double size, Rng& rng) {
  LineMap m;
  m.name = "random";
  m.segments.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d p1(rng.uniform(0.0, size), rng.uniform(0.0, size));
    const double a = rng.uniform(-kPi, kPi), len = rng.uniform(0.3, 3.0);
    m.segments.push_back({p1, p1 + len * Eigen::Vector2d(std::cos(a), std::sin(a))});
  }
  return m;
}

}  // namespace locbench::laser::test
