#pragma once
// Plumbing shared by every compass-aided odometry EKF (algorithms/filters and baselines/filters):
// state X = [x, y, θ]ᵀ (eq. 3.27, 4.1), motion model F(X, k−1) with its Jacobian ∇F (eq. 4.1–4.2),
// and the compass measurement Z = H X + V, H = [0 0 1] (eq. 3.28, 4.45). Header-only so the
// 3-state step stays inlinable; SI units (m, rad).
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>

#include "core/angle.h"
#include "core/diff_drive_odometry.h"
#include "core/pose2.h"

namespace locbench {

using Vector3 = Eigen::Vector3d;

inline Vector3 to_vector(const Pose2& p) { return {p.x, p.y, p.theta}; }
inline Pose2 to_pose(const Vector3& x) { return {x(0), x(1), x(2)}; }

inline Matrix3 symmetrize(const Matrix3& m) { return 0.5 * (m + m.transpose()); }

// True when the symmetric matrix admits a Cholesky factorisation (all pivots > 0).
inline bool is_positive_definite(const Matrix3& m) {
  Eigen::LLT<Matrix3> llt(m);
  return llt.info() == Eigen::Success;
}

// F(X̂(k−1), k−1) and ∇F = ∂F/∂X at X̂(k−1) (eq. 4.1–4.2); θ of the mean wrapped to [−π, π).
struct MotionPrediction {
  Vector3 mean = Vector3::Zero();
  Matrix3 jacobian = Matrix3::Identity();
};
inline MotionPrediction predict_motion(const Vector3& x, const WheelDisplacement& u, double wheelbase) {
  const Pose2 p = to_pose(x);
  return {to_vector(odometry_step(p, u, wheelbase)), odometry_jacobian_pose(p, u, wheelbase)};
}

// The compass innovation for a predicted state: ε = Z − (H X̂(k/k−1) + r̂) wrapped to [−π, π),
// S = H P Hᵀ + R, K = P Hᵀ S⁻¹ (eq. 3.28, 4.45; r̂ is the Sage–Husa measurement-noise mean).
struct CompassInnovation {
  double innovation = 0.0;  // ε [rad]
  double variance = 0.0;    // S [rad²]
  Vector3 gain = Vector3::Zero();
};
inline CompassInnovation compass_innovation(const Vector3& x_pred, const Matrix3& p_pred, double heading,
                                            double r_variance, double r_mean = 0.0) {
  CompassInnovation c;
  c.innovation = angle_diff(heading, x_pred(2) + r_mean);
  c.variance = p_pred(2, 2) + r_variance;
  c.gain = p_pred.col(2) / c.variance;
  return c;
}

// X̂(k/k) = X̂(k/k−1) + K ε, P(k) = (I − K H) P(k/k−1) (symmetrised).
inline void apply_compass_update(Vector3& x, Matrix3& p, const CompassInnovation& c) {
  x += c.gain * c.innovation;
  x(2) = wrap_angle(x(2));
  const Eigen::RowVector3d h_p = p.row(2);  // H P
  p -= c.gain * h_p;
  p = symmetrize(p);
}

// One filter step as returned by the compass EKFs: the posterior (or the prediction when no
// compass reading came) and, when updated, the innovation and its variance for the NIS.
struct CompassFilterStep {
  Vector3 mean = Vector3::Zero();
  Matrix3 covariance = Matrix3::Zero();
  bool updated = false;
  double innovation = 0.0;           // ε [rad]
  double innovation_variance = 0.0;  // S [rad²]

  Pose2 pose() const { return to_pose(mean); }

  // The state after the step, and the innovation `c` when a compass reading updated it.
  void record(const Vector3& x, const Matrix3& p, const CompassInnovation* c) {
    mean = x;
    covariance = p;
    if (c) {
      updated = true;
      innovation = c->innovation;
      innovation_variance = c->variance;
    }
  }
};

// One step of the plain compass EKF with process noise Q and compass variance R: the prediction
// X̂(k/k−1) = F(X̂(k−1)), P(k/k−1) = ∇F P ∇Fᵀ + Q (eq. 4.1–4.2), then, when a heading came, the
// compass update (eq. 4.45). Updates x and p in place.
inline CompassFilterStep compass_ekf_step(Vector3& x, Matrix3& p, const WheelDisplacement& u, double wheelbase,
                                          const Matrix3& q, std::optional<double> heading, double r_variance) {
  const MotionPrediction pred = predict_motion(x, u, wheelbase);
  x = pred.mean;
  p = symmetrize(pred.jacobian * p * pred.jacobian.transpose() + q);
  std::optional<CompassInnovation> c;
  if (heading) {
    c = compass_innovation(x, p, *heading, r_variance);
    apply_compass_update(x, p, *c);
  }
  CompassFilterStep out;
  out.record(x, p, c ? &*c : nullptr);
  return out;
}

}  // namespace locbench
