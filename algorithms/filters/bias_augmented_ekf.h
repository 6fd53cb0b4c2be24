#pragma once
// The EKF of a fitted motion model whose noise is correlated in time, in its landmark sensor, its
// motion, or both: the pose state is augmented by first-order Gauss–Markov processes (state
// augmentation for coloured noise; Gelb, "Applied Optimal Estimation", 1974, §4.5):
//   X = [x, y, θ, b_r, b_φ, m_x, m_y, m_θ, l]ᵀ,  b(k) = a·b(k−1) + w,  a = e^(−Δt/τ),  var w = σ_b²(1 − a²).
// - b_r, b_φ: a range and a bearing bias shared by all landmarks,
//   z = h(x, y, θ) + [b_r, b_φ]ᵀ + v,  v white with the measurement's own R; a compass reading sees
//   no bias.
// - m_x, m_y, m_θ: the motion error that persists between steps, each of unit variance. A step's
//   model covariance Σ (in the robot frame at its start, diagonal) splits into a white part
//   (1 − s)·Σ and a correlated part: the increment in the robot frame moves by
//   A·m, A = diag(√(s·Σ_jj·Δt / w)), so that over a window of length w the correlated part has
//   variance s·Σ_w, the share s of the window residuals' variance that the diagnosis finds
//   correlated over windows, with correlation time τ (what the extended twin draws).
// - l: drive stalls, as the deviation of the fraction of the commanded translation lost from its
//   mean (which the step's increment already takes off): a stall holds the robot back over
//   several steps, so the loss is correlated in time. The increment moves by −l·D along the track,
//   D the step's translation before the loss. (A two-state stall chain with stationary probability
//   π and correlation time τ has exactly these first two moments: mean π, variance π(1 − π),
//   correlation e^(−Δt/τ); the EKF is its best linear estimator.)
// The pose part predicts as MotionModelEkf (eq. 4.1–4.2 with the model's covariance in the robot
// frame) plus A·m rotated into the world frame. With σ_b = 0 and s = 0 the added states stay 0
// and the filter is MotionModelEkf.
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

// The correlated share s and correlation time τ of the motion noise along, left and in heading,
// for the model's noise window w (diagnosis: noise_window_s).
struct MotionNoiseCorrelation {
  Vector3 share = Vector3::Zero();
  Vector3 time_s = Vector3::Ones();  // [s]
  double window_s = 1.0;             // [s]
  GaussMarkovBias stall;             // the stall loss l: σ of the lost fraction (0: no stall state), τ
};

class BiasAugmentedEkf {
 public:
  static constexpr int kStates = 9;
  using StateVector = Eigen::Matrix<double, kStates, 1>;
  using StateMatrix = Eigen::Matrix<double, kStates, kStates>;

  // The added states start at 0 with their stationary variance. Throws UsageError for wheelbase
  // <= 0, an initial covariance that is not finite, a bias with σ < 0 or τ <= 0, or a motion
  // share outside [0, 1), τ <= 0 or w <= 0.
  BiasAugmentedEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance,
                   const MeasurementBiasModel& bias, const MotionNoiseCorrelation& motion = {});

  // Predict over dt [s] with the wheel travel u of the model's increment and its covariance in
  // the robot frame at the step's start (its correlated share moved by the motion states), and
  // the step's translation before the stall loss, `stall_distance` [m] (what l acts on); the
  // added states decay toward 0 over dt.
  void predict(const WheelDisplacement& u, const Matrix3& body_covariance, double dt, double stall_distance = 0.0);
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);
  // The innovation ν of z at the current state and its covariance S, the added states'
  // uncertainty included (nothing changes; no gain).
  MeasurementUpdate innovation(const PoseMeasurement& z) const;
  // νᵀS⁻¹ν of z at the current state (nothing changes).
  double nis(const PoseMeasurement& z) const;

  Vector3 mean() const { return x_.head<3>(); }
  Matrix3 covariance() const { return p_.topLeftCorner<3, 3>(); }
  Eigen::Vector2d bias() const { return x_.segment<2>(3); }
  Vector3 motion_error() const { return x_.segment<3>(5); }  // m_x, m_y, m_θ (unit variance)
  double stall_loss() const { return x_(8); }                // l

 private:
  struct Linearized {
    LinearizedMeasurement pose;  // h and H of the pose part
    MeasurementVector offset;    // the biases the measurement sees
    Eigen::Matrix<double, Eigen::Dynamic, kStates, 0, 2, kStates> H;
  };
  Linearized linearize_full(const PoseMeasurement& z) const;

  double wheelbase_;
  MeasurementBiasModel bias_;
  MotionNoiseCorrelation motion_;
  StateVector x_;
  StateMatrix p_;
};

}  // namespace locbench::filters
