#pragma once
// Map segment P1P2 and its normal form x cosβ + y sinβ − ρ = 0 (eq. 5.1), ρ ≥ 0.
#include <Eigen/Core>

namespace locbench {

struct LineParams {
  double rho = 0.0;   // distance of the infinite line from the origin [m], ≥ 0
  double beta = 0.0;  // direction of the line's normal [rad], in [-π, π)
};

struct Segment {
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();
  Eigen::Vector2d p2 = Eigen::Vector2d::Zero();

  double length() const { return (p2 - p1).norm(); }
  LineParams line() const;  // eq. 5.1
};

// Signed distance of p from the infinite line (positive on the side the normal points to).
double signed_distance_to_line(const LineParams& line, const Eigen::Vector2d& p);
// Euclidean distance from p to the closed segment.
double distance_to_segment(const Segment& s, const Eigen::Vector2d& p);

}  // namespace locbench
