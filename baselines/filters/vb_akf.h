#pragma once
// Baseline: the variational-Bayes adaptive Kalman filter of
//   S. Särkkä and A. Nummenmaa, "Recursive noise adaptive Kalman filtering by variational
//   Bayesian approximations", IEEE Transactions on Automatic Control 54(3):596–600, 2009,
//   doi:10.1109/TAC.2008.2008348,
// in its extended (EKF) form for the compass EKF: the process noise Q is fixed (the published
// diag(6.33 mm², 6.33 mm², 2 deg²)) and the compass noise variance σ² is estimated online with an
// inverse-gamma posterior IG(α, β):
//   prediction:  X̂⁻ = F(X̂), P⁻ = ∇F P ∇Fᵀ + Q,  α⁻ = ρ α,  β⁻ = ρ β   (ρ ∈ (0, 1] forgetting)
//   update:      α = α⁻ + 1/2;  β ← β⁻; repeat N times:
//                  R = β/α, S = H P⁻ Hᵀ + R, K = P⁻Hᵀ/S, X̂ = X̂⁻ + K ε, P = P⁻ − K S Kᵀ,
//                  β = β⁻ + ½ (Z − H X̂)² + ½ H P Hᵀ
// (ε = Z − H X̂⁻ wrapped to [−π, π)). The filter's R is the plug-in β/α. Any measurement of
// core/pose_measurement.h can be used: each kind keeps its own α and one β per component (the
// paper's diagonal R: range and bearing have independent inverse-gamma posteriors); the compass's
// start at the options' prior, another kind's at its first measurement (β = α(0)·its own R). A
// measurement whose NIS under the prior plug-in R exceeds the gate changes nothing.
#include <array>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/compass_ekf_model.h"
#include "core/units.h"

namespace locbench::baselines::filters {

struct VbAkfOptions {
  // diag Q [m², m², rad²]: the published fixed Q (§4.5).
  Vector3 process_noise{mm(1.0) * mm(1.0) * 6.33, mm(1.0) * mm(1.0) * 6.33, 2.0 * deg(1.0) * deg(1.0)};
  // Prior of the compass variance: β(0) = α(0) · initial_measurement_variance.
  double initial_measurement_variance = 2.0 * deg(1.0) * deg(1.0);  // 2 deg² [rad²]
  double initial_shape = 1.0;                                       // α(0) > 0
  // ρ: α and β shrink by ρ per sample; steady-state α = 1/(2(1 − ρ)), i.e. a memory of about
  // 1/(1 − ρ) compass readings (our choice: 100 readings = 25 s at 4 Hz).
  double forgetting = 0.99;
  int iterations = 3;                            // N fixed-point iterations per update (the paper: 2–3 suffice)
  Vector3 initial_covariance = Vector3::Zero();  // diag P(0)
};
void to_json(nlohmann::json& j, const VbAkfOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, VbAkfOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const VbAkfOptions& o);

struct VbAkfStep {
  CompassFilterStep filter;
  double shape = 0.0;                 // α(k)
  double scale = 0.0;                 // β(k)
  double measurement_variance = 0.0;  // β/α [rad²]
};

class VbAkf : public PoseGaussian {
 public:
  // Throws UsageError for invalid options or wheelbase <= 0.
  VbAkf(const VbAkfOptions& options, double wheelbase, const Pose2& start);

  // One encoder sample: predict with u; with a compass heading [rad], the VB update.
  VbAkfStep step(const WheelDisplacement& u, std::optional<double> compass_heading);

  // The prediction alone, Q·noise_scale (1 per sample; a step of another length passes its ratio
  // to the sample period); α, β forget by ρ.
  void predict(const WheelDisplacement& u, double noise_scale = 1.0);
  // The VB correction with any measurement, skipped when NIS > gate.
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate);

  // The compass's plug-in R = β/α.
  double measurement_variance() const { return noise_[0].beta(0) / noise_[0].alpha; }

 private:
  // The inverse-gamma posterior of one measurement kind's noise variances.
  struct NoisePosterior {
    bool started = false;
    double alpha = 0.0;
    MeasurementVector beta;
  };

  Matrix3 q_;
  double rho_;
  int iterations_;
  double initial_shape_;
  double wheelbase_;
  std::array<NoisePosterior, kMeasurementKinds> noise_;
};

}  // namespace locbench::baselines::filters
