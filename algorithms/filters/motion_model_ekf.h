#pragma once
// The EKF of a fitted motion model (the model `locbench diagnose` fits, or its nominal form):
// the prediction is the model's own increment over the step, and the process noise is the
// model's covariance of that increment, given in the robot frame at the step's start (x along,
// y left, θ — the frame of the diagnosis's window residuals) and rotated into the world frame:
//   X̂(k/k−1) = F(X̂(k−1), u),  P(k/k−1) = ∇F P ∇Fᵀ + G Σ_body Gᵀ,  G = diag(R(θ̂(k−1)), 1)
// (eq. 4.1–4.2 with the process noise of the model instead of eq. 4.43–4.44). The correction
// is the plain EKF update with any absolute measurement (core/pose_measurement.h).
#include "core/compass_ekf_model.h"

namespace locbench::filters {

class MotionModelEkf : public PoseGaussian {
 public:
  // Throws UsageError for wheelbase <= 0 or an initial covariance that is not finite.
  MotionModelEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance);

  // Predict with the wheel travel u of the model's increment and its covariance in the robot
  // frame at the step's start.
  void predict(const WheelDisplacement& u, const Matrix3& body_covariance);
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);

 private:
  double wheelbase_;
};

// G Σ Gᵀ: a covariance in the robot frame at heading θ expressed in the world frame.
Matrix3 body_to_world_covariance(const Matrix3& body, double theta);

}  // namespace locbench::filters
