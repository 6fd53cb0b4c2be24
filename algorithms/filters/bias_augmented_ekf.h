#pragma once
// The EKF of a fitted motion model whose landmark sensor has noise correlated in time: the pose
// state is augmented by a range bias and a bearing bias shared by all landmarks, each a first-order
// Gauss–Markov process (state augmentation for coloured measurement noise; Gelb, "Applied Optimal
// Estimation", 1974, §4.5):
//   X = [x, y, θ, b_r, b_φ]ᵀ,  b(k) = a·b(k−1) + w,  a = e^(−Δt/τ),  var w = σ_b²(1 − a²),
//   z = h(x, y, θ) + [b_r, b_φ]ᵀ + v,  v white with the measurement's own R.
// The pose part predicts exactly as MotionModelEkf (eq. 4.1–4.2 with the model's covariance in the
// robot frame); a compass reading sees no bias. With σ_b = 0 the biases stay 0 and the filter is
// MotionModelEkf.
#include <Eigen/Core>

#include "core/compass_ekf_model.h"

namespace locbench::filters {

// One Gauss–Markov bias: its stationary standard deviation and correlation time.
struct GaussMarkovBias {
  double sigma = 0.0;   // [m] or [rad]
  double time_s = 1.0;  // τ [s]
};

struct MeasurementBiasModel {
  GaussMarkovBias range, bearing;
};

class BiasAugmentedEkf {
 public:
  using Vector5 = Eigen::Matrix<double, 5, 1>;
  using Matrix5 = Eigen::Matrix<double, 5, 5>;

  // The biases start at 0 with their stationary variance. Throws UsageError for wheelbase <= 0,
  // an initial covariance that is not finite, or a bias with σ < 0 or τ <= 0.
  BiasAugmentedEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance,
                   const MeasurementBiasModel& bias);

  // Predict over dt [s] with the wheel travel u of the model's increment and its covariance in
  // the robot frame at the step's start; the biases decay toward 0 over dt.
  void predict(const WheelDisplacement& u, const Matrix3& body_covariance, double dt);
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);
  // νᵀS⁻¹ν of z at the current state, the biases' uncertainty included (nothing changes).
  double nis(const PoseMeasurement& z) const;

  Vector3 mean() const { return x_.head<3>(); }
  Matrix3 covariance() const { return p_.topLeftCorner<3, 3>(); }
  Eigen::Vector2d bias() const { return x_.tail<2>(); }

 private:
  struct Linearized {
    LinearizedMeasurement pose;  // h and H of the pose part
    MeasurementVector offset;    // the biases the measurement sees
    Eigen::Matrix<double, Eigen::Dynamic, 5, 0, 2, 5> H;
  };
  Linearized linearize_full(const PoseMeasurement& z) const;

  double wheelbase_;
  MeasurementBiasModel bias_;
  Vector5 x_;
  Matrix5 p_;
};

}  // namespace locbench::filters
