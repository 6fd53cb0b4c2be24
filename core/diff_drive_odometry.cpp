#include "core/diff_drive_odometry.h"

#include <cmath>
#include <string>

#include "core/errors.h"

namespace locbench {

Pose2 odometry_step(const Pose2& p, const WheelDisplacement& u, double wheelbase) {
  const BodyIncrement d = body_increment(u, wheelbase);
  const double mid = p.theta + 0.5 * d.rotation;
  return {p.x + d.distance * std::cos(mid), p.y + d.distance * std::sin(mid), p.theta + d.rotation};
}

Pose2 exact_arc_step(const Pose2& p, const WheelDisplacement& u, double wheelbase) {
  const BodyIncrement d = body_increment(u, wheelbase);
  const double half = 0.5 * d.rotation;
  const double chord =
      std::abs(half) < 1e-4 ? d.distance * (1.0 - half * half / 6.0) : d.distance * std::sin(half) / half;
  const double mid = p.theta + half;
  return {p.x + chord * std::cos(mid), p.y + chord * std::sin(mid), p.theta + d.rotation};
}

Matrix3 odometry_jacobian_pose(const Pose2& p, const WheelDisplacement& u, double wheelbase) {
  const BodyIncrement d = body_increment(u, wheelbase);
  const double mid = p.theta + 0.5 * d.rotation;
  Matrix3 F = Matrix3::Identity();
  F(0, 2) = -d.distance * std::sin(mid);
  F(1, 2) = d.distance * std::cos(mid);
  return F;
}

Matrix32 odometry_jacobian_wheels(const Pose2& p, const WheelDisplacement& u, double wheelbase) {
  const BodyIncrement d = body_increment(u, wheelbase);
  const double mid = p.theta + 0.5 * d.rotation;
  const double c = std::cos(mid), s = std::sin(mid);
  const double h = d.distance / (2.0 * wheelbase);
  Matrix32 F;
  F << 0.5 * c - h * s, 0.5 * c + h * s,  //
      0.5 * s + h * c, 0.5 * s - h * c,   //
      1.0 / wheelbase, -1.0 / wheelbase;
  return F;
}

Matrix3 propagate_covariance(const Matrix3& sigma, const Pose2& p, const WheelDisplacement& u, double wheelbase,
                             const WheelNoise& noise) {
  const Matrix3 Fp = odometry_jacobian_pose(p, u, wheelbase);
  const Matrix32 Fu = odometry_jacobian_wheels(p, u, wheelbase);
  Eigen::Matrix2d sigma_u = Eigen::Matrix2d::Zero();
  sigma_u(0, 0) = noise.k_right * std::abs(u.right);
  sigma_u(1, 1) = noise.k_left * std::abs(u.left);
  return Fp * sigma * Fp.transpose() + Fu * sigma_u * Fu.transpose();
}

void require_positive_wheelbase(double wheelbase, const char* who) {
  if (!(wheelbase > 0.0) || !std::isfinite(wheelbase)) {
    throw UsageError(std::string(who) + ": wheelbase must be > 0");
  }
}

}  // namespace locbench
