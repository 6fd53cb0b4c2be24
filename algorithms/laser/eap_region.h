#pragma once
// The Effective Area of Plane ω1 of a map segment P1P2 (§5.3, eq. 5.12–5.17): where a scan
// point (world frame, under the pose estimate) may lie if its beam hit that segment's plane.
//   ω2 = {p : |p·n − ρ| ≤ d_limit}                   band about the infinite line (5.5)
//   d1 = |p − P1|, d2 = |p − P2|                      (5.12–5.13)
//   d3 = √(d_limit² + |P1P2|²)                        (5.14)
//   ω3 = {p ∈ ω2 : max(d1, d2) > d3 and min(d1, d2) > d_limit}   beyond the end caps (5.15–5.17)
//   ω1 = ω2 \ ω3
// Checked (proof in eap_region.cpp, 10⁶ random points in the test): ω1 is *exactly* the stadium
// {p : distance(p, closed segment P1P2) ≤ d_limit}, for every length and d_limit — the thesis's
// ω3 removes precisely the band's points outside the two end discs. The two rules can only
// disagree by rounding on the boundary. Both are offered; kThesis is the default.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/segment.h"

namespace locbench::laser {

enum class RegionRule {
  kThesis,   // ω2 \ ω3 as published (5.12–5.17), compared in squared distances
  kStadium,  // distance to the closed segment ≤ d_limit
};
const char* to_string(RegionRule r);
// "thesis" | "stadium"; throws UsageError otherwise.
RegionRule region_rule_from_string(const std::string& s);

// One segment's ω1 with everything the membership test needs precomputed.
class EapRegion {
 public:
  // Throws UsageError for a zero-length segment or d_limit not finite and > 0.
  EapRegion(const Segment& segment, double d_limit);

  // p ∈ ω1 under `rule`. Inline: this is the matcher's inner loop.
  bool contains(const Eigen::Vector2d& p, RegionRule rule) const {
    const Eigen::Vector2d q = p - p1_;
    const double h = normal_.dot(q);               // signed distance from the line
    if (!(std::abs(h) <= d_limit_)) return false;  // ω2 (5.5); rejects NaN too
    if (rule == RegionRule::kThesis) {
      const double d1s = q.squaredNorm();          // d1² (5.12)
      const double d2s = (p - p2_).squaredNorm();  // d2² (5.13)
      const bool in_omega3 =                       // (5.15–5.17) with d3² (5.14)
          std::max(d1s, d2s) > d3_squared_ && std::min(d1s, d2s) > d_limit_squared_;
      return !in_omega3;
    }
    const double t = direction_.dot(q);  // position along P1→P2
    if (t < 0.0) return q.squaredNorm() <= d_limit_squared_;
    if (t > length_) return (p - p2_).squaredNorm() <= d_limit_squared_;
    return true;
  }

  // Euclidean distance from p to the closed segment (used to give a point claimed by several
  // regions to the nearest segment).
  double distance_to_segment(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = p - p1_;
    const double t = std::clamp(direction_.dot(q), 0.0, length_);
    return (q - t * direction_).norm();
  }

  double d_limit() const { return d_limit_; }
  double length() const { return length_; }
  const Eigen::Vector2d& p1() const { return p1_; }
  const Eigen::Vector2d& p2() const { return p2_; }
  const Eigen::Vector2d& direction() const { return direction_; }  // unit, P1 → P2
  const Eigen::Vector2d& normal() const { return normal_; }        // unit, left of direction()
  double d3_squared() const { return d3_squared_; }                // d3² (5.14)

 private:
  Eigen::Vector2d p1_;
  Eigen::Vector2d p2_;
  Eigen::Vector2d direction_;  // unit, P1 → P2
  Eigen::Vector2d normal_;     // unit, left of direction_
  double length_ = 0.0;
  double d_limit_ = 0.0;
  double d_limit_squared_ = 0.0;
  double d3_squared_ = 0.0;  // d3² = d_limit² + |P1P2|² (5.14)
};

}  // namespace locbench::laser
