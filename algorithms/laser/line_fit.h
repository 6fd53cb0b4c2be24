#pragma once
// Least-squares line through points: the orthogonal (total) least-squares fit, i.e. the line
// minimising the sum of squared perpendicular distances, in the normal form of eq. 5.1.
#include <Eigen/Core>
#include <span>

#include "core/segment.h"

namespace locbench::laser {

struct LineFit {
  LineParams line;  // ρ ≥ 0, β ∈ [-π, π)
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // unit, along the line
  double rms = 0.0;                                      // root-mean-square perpendicular residual [m]
  std::size_t count = 0;
  // The fitted segment: the first and last point projected onto the line.
  Segment segment() const { return {first, last}; }
  Eigen::Vector2d first = Eigen::Vector2d::Zero();
  Eigen::Vector2d last = Eigen::Vector2d::Zero();
};

// Needs at least two distinct points (otherwise count < 2 and the line is meaningless);
// the points' order decides `first` and `last`.
LineFit fit_line(std::span<const Eigen::Vector2d> points);

}  // namespace locbench::laser
