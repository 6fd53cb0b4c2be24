#pragma once
// Baseline: the compass EKF with a fixed, experience-based process noise ("the second EKF" of
// §4.5): X̂(k/k−1) = F(X̂(k−1)), P(k/k−1) = ∇F P(k−1) ∇Fᵀ + Q, compass update with fixed R
// (eq. 3.27–3.28, 4.1, 4.45). Published settings: Q = diag(6.33, 6.33, 2) and R = 2, printed
// in mm², mm², deg² and converted here to m², m², rad².
#include <nlohmann/json.hpp>
#include <optional>

#include "core/compass_ekf_model.h"
#include "core/units.h"

namespace locbench::baselines::filters {

struct FixedQEkfOptions {
  // diag Q [m², m², rad²] = diag(6.33 mm², 6.33 mm², 2 deg²) (§4.5).
  Vector3 process_noise{mm(1.0) * mm(1.0) * 6.33, mm(1.0) * mm(1.0) * 6.33, 2.0 * deg(1.0) * deg(1.0)};
  double compass_variance = 2.0 * deg(1.0) * deg(1.0);  // R = 2 deg² [rad²]
  Vector3 initial_covariance = Vector3::Zero();         // diag P(0)
};
void to_json(nlohmann::json& j, const FixedQEkfOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, FixedQEkfOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const FixedQEkfOptions& o);

class FixedQEkf : public PoseGaussian {
 public:
  // Throws UsageError for invalid options or wheelbase <= 0.
  FixedQEkf(const FixedQEkfOptions& options, double wheelbase, const Pose2& start);

  // One encoder sample: predict with the wheel travel u, then correct with the compass heading
  // [rad] if one came with it.
  CompassFilterStep step(const WheelDisplacement& u, std::optional<double> compass_heading);

  // The prediction alone with Q·noise_scale (1 per sample; a step of another length passes its
  // ratio to the sample period).
  void predict(const WheelDisplacement& u, double noise_scale = 1.0);
  // The correction with any absolute measurement (its own R), skipped when NIS > gate.
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);

 private:
  Matrix3 q_;
  double r_;
  double wheelbase_;
};

}  // namespace locbench::baselines::filters
