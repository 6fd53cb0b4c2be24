#pragma once
// Plumbing shared by every odometry EKF (algorithms/filters and baselines/filters): state
// X = [x, y, θ]ᵀ (eq. 3.27, 4.1), motion model F(X, k−1) with its Jacobian ∇F (eq. 4.1–4.2), and
// the correction with any absolute measurement of core/pose_measurement.h — the compass
// Z = H X + V, H = [0 0 1] (eq. 3.28, 4.45), or a landmark's range and bearing — with an optional
// Mahalanobis gate. SI units (m, rad). The steps that factorise or multiply matrices are defined in
// compass_ekf_model.cpp: inline here, every translation unit including this header instantiated
// their Eigen templates (LLT, LDLT of the 2×2-capacity S, the mixed-size products) again.
#include <Eigen/Core>
#include <limits>
#include <optional>

#include "core/angle.h"
#include "core/diff_drive_odometry.h"
#include "core/pose2.h"
#include "core/pose_measurement.h"

namespace locbench {

using Vector3 = Eigen::Vector3d;

inline Vector3 to_vector(const Pose2& p) { return {p.x, p.y, p.theta}; }
inline Pose2 to_pose(const Vector3& x) { return {x(0), x(1), x(2)}; }

inline Matrix3 symmetrize(const Matrix3& m) { return 0.5 * (m + m.transpose()); }

// True when the symmetric matrix admits a Cholesky factorisation (all pivots > 0).
bool is_positive_definite(const Matrix3& m);

// F(X̂(k−1), k−1) and ∇F = ∂F/∂X at X̂(k−1) (eq. 4.1–4.2); θ of the mean wrapped to [−π, π).
struct MotionPrediction {
  Vector3 mean = Vector3::Zero();
  Matrix3 jacobian = Matrix3::Identity();
};
MotionPrediction predict_motion(const Vector3& x, const WheelDisplacement& u, double wheelbase);

// The EKF prediction X̂(k/k−1) = F(X̂(k−1)), P(k/k−1) = ∇F P ∇Fᵀ + Q (eq. 4.1–4.2), in place.
void ekf_predict(Vector3& x, Matrix3& p, const WheelDisplacement& u, double wheelbase, const Matrix3& q);

// No Mahalanobis gate: every measurement is used.
inline constexpr double kNoGate = std::numeric_limits<double>::infinity();

// The correction with a linearised measurement, noise R and an optional mean r̂:
//   ν = z − (h(X̂) + r̂), S = H P Hᵀ + R, K = P Hᵀ S⁻¹, NIS = νᵀ S⁻¹ ν.
// (For the compass H = [0 0 1], S = P_θθ + R and K = P_·θ / S exactly as eq. 3.28, 4.45.)
struct MeasurementUpdate {
  MeasurementVector innovation;             // ν
  MeasurementMatrix innovation_covariance;  // S
  MeasurementGain gain;                     // K
  double nis = 0.0;                         // νᵀ S⁻¹ ν
  bool gated = false;                       // NIS above the gate: not applied
};
MeasurementUpdate measurement_innovation(const LinearizedMeasurement& m, const Matrix3& p, const MeasurementMatrix& r,
                                         const MeasurementVector* r_mean = nullptr);

// X̂(k/k) = X̂(k/k−1) + K ν, P(k) = (I − K H) P(k/k−1) (symmetrised).
void apply_measurement_update(Vector3& x, Matrix3& p, const MeasurementUpdate& u, const LinearizedMeasurement& m);

// Linearise at X̂, gate on the NIS, correct: the plain EKF update with the measurement's own R.
// Returns the update (gated = true and nothing changed when NIS > gate).
MeasurementUpdate ekf_update(Vector3& x, Matrix3& p, const PoseMeasurement& z, double gate = kNoGate);

// One filter step as returned by the compass EKFs: the posterior (or the prediction when no
// compass reading came) and, when updated, the innovation and its variance for the NIS.
struct CompassFilterStep {
  Vector3 mean = Vector3::Zero();
  Matrix3 covariance = Matrix3::Zero();
  bool updated = false;
  double innovation = 0.0;           // ε [rad]
  double innovation_variance = 0.0;  // S [rad²]

  Pose2 pose() const { return to_pose(mean); }

  // The state after the step, and the compass update `c` when a reading updated it.
  void record(const Vector3& x, const Matrix3& p, const MeasurementUpdate* c) {
    mean = x;
    covariance = p;
    if (c && !c->gated) {
      updated = true;
      innovation = c->innovation(0);
      innovation_variance = c->innovation_covariance(0, 0);
    }
  }
};

// The state every Kalman filter of the pose keeps: X̂ = [x, y, θ]ᵀ and its covariance P.
class PoseGaussian {
 public:
  Pose2 pose() const { return to_pose(x_); }
  const Vector3& mean() const { return x_; }
  const Matrix3& covariance() const { return p_; }

 protected:
  PoseGaussian(const Vector3& x, const Matrix3& p) : x_(x), p_(p) {}

  Vector3 x_;
  Matrix3 p_;
};

}  // namespace locbench
