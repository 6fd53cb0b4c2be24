#pragma once
// SE(2) pose: position (x, y) in metres and heading θ in radians, θ kept in [-π, π).
#include <Eigen/Core>
#include <cmath>

#include "core/angle.h"

namespace locbench {

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Pose2() = default;
  Pose2(double x_, double y_, double theta_) : x(x_), y(y_), theta(wrap_angle(theta_)) {}

  static Pose2 identity() { return {}; }
  Eigen::Vector2d translation() const { return {x, y}; }

  // this ∘ other: `other` expressed in this pose's frame, mapped to the parent frame.
  Pose2 operator*(const Pose2& other) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * other.x - s * other.y, y + s * other.x + c * other.y, theta + other.theta};
  }
  Pose2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, -theta};
  }
  // Maps a point from this pose's frame to the parent frame.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
};

// Relative motion from a to b expressed in a's frame: a⁻¹ ∘ b.
inline Pose2 between(const Pose2& a, const Pose2& b) { return a.inverse() * b; }

inline double translation_distance(const Pose2& a, const Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

}  // namespace locbench
