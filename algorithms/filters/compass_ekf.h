#pragma once
// The compass-aided odometry EKF of eq. 3.27–3.28 / §4.5 ("the third EKF"): state [x, y, θ],
// prediction by the odometry of one encoder sample (eq. 4.1), measurement = compass heading
// (eq. 4.45), with a pluggable process-noise model: by default the thesis's adaptive per-sample
// Q(k−1) (eq. 4.36–4.44, odometry_noise_model.h). The fixed-Q EKF and the adaptive baselines
// live in baselines/filters.
//   X̂(k/k−1) = F(X̂(k−1)),  P(k/k−1) = ∇F P(k−1) ∇Fᵀ + Q(k−1)
//   K = P(k/k−1)Hᵀ[H P(k/k−1) Hᵀ + R]⁻¹,  X̂(k) = X̂(k/k−1) + K ε,  P(k) = (I − K H) P(k/k−1)
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "algorithms/filters/odometry_noise_model.h"
#include "core/compass_ekf_model.h"

namespace locbench::filters {

struct CompassEkfOptions {
  OdometryNoiseOptions noise;                           // k_l = k_r = 0.005 √m, σ = 5.00 mm
  double compass_variance = 2.0 * deg(1.0) * deg(1.0);  // R = 2 deg² (§4.5) [rad²]
  // diag P(0) [m², m², rad²]; the thesis starts from a known pose, P(0) = 0.
  Vector3 initial_covariance = Vector3::Zero();
  // Multiplies Q(k−1): 1 = as modelled, < 1 makes the filter over-confident (for tests and
  // sensitivity sweeps).
  double process_noise_scale = 1.0;
};
void to_json(nlohmann::json& j, const CompassEkfOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, CompassEkfOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const CompassEkfOptions& o);

// Q(k−1) from the previous estimate X̂(k−1), the sample's wheel travel and the wheelbase.
using ProcessNoiseModel = std::function<Matrix3(const Vector3& x_prev, const WheelDisplacement& u, double wheelbase)>;

class CompassEkf : public PoseGaussian {
 public:
  // The thesis's adaptive model. Throws UsageError for invalid options or wheelbase <= 0.
  CompassEkf(const CompassEkfOptions& options, double wheelbase, const Pose2& start);
  // Any process-noise model (e.g. a fixed or deliberately wrong Q).
  CompassEkf(ProcessNoiseModel process_noise, double compass_variance, const Matrix3& initial_covariance,
             double wheelbase, const Pose2& start);

  // One sample: predict with the wheel travel u, then correct with the compass heading [rad]
  // if one came with this sample.
  CompassFilterStep step(const WheelDisplacement& u, std::optional<double> compass_heading);

  // The prediction alone, Q(k−1) multiplied by `noise_scale` (1 per sample of the model's
  // period; a step of another length passes its ratio).
  void predict(const WheelDisplacement& u, double noise_scale = 1.0);
  // The correction with any absolute measurement (its own R), skipped when NIS > gate.
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);

 private:
  Matrix3 process_noise(const WheelDisplacement& u) const;

  ProcessNoiseModel custom_q_;  // empty: the adaptive model of options_
  CompassEkfOptions options_;
  double wheelbase_;
};

}  // namespace locbench::filters
