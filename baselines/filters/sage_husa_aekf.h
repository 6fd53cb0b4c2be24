#pragma once
// Baseline: the adaptive EKF of §4.2/§4.5 ("the first EKF") — Sage & Husa's suboptimal MAP
// noise-statistics estimator (A. P. Sage, G. W. Husa, "Adaptive filtering with unknown prior
// statistics", JACC 1969) with Deng's exponential forgetting (邓自立, 王建国, 自动化学报 13(5),
// 1987) and Zhang's positive-definiteness fix (张友民, 张洪才, 戴冠中, 西北工业大学学报 11(3),
// 1993), exactly as the thesis writes them (README.md of algorithms/filters):
//   X̂(k/k−1) = F(X̂(k−1)) + q̂(k−1),  Ẑ(k) = H X̂(k/k−1) + r̂(k−1),  ε(k) = Z(k) − Ẑ(k)
//   P(k/k−1) = ∇F P(k−1) ∇Fᵀ + Q̂(k−1),  K = P(k/k−1)Hᵀ[H P(k/k−1) Hᵀ + R̂(k−1)]⁻¹
//   X̂(k/k) = X̂(k/k−1) + K ε,  P(k) = (I − K H) P(k/k−1)
//   d(k−1) = (1 − b)/(1 − b^k)                                                   (eq. 4.9)
//   q̂(k) = (1 − d) q̂(k−1) + d [X̂(k/k) − F(X̂(k−1))]                              (eq. 4.10)
//   Q̂(k) = (1 − d) Q̂(k−1) + d [K ε εᵀ Kᵀ + P(k) − ∇F P(k−1) ∇Fᵀ]                 (eq. 4.11)
//   r̂(k) = (1 − d) r̂(k−1) + d [Z(k) − H X̂(k/k−1)]
//   R̂(k) = (1 − d) R̂(k−1) + d [ε εᵀ − H P(k/k−1) Hᵀ]
// Zhang's fix: if Q̂(k) is not positive definite, Q̂(k) += d (∇F P(k−1) ∇Fᵀ − P(k)); if R̂(k) is
// not, R̂(k) += d H P(k/k−1) Hᵀ — i.e. the subtracted term is dropped for that step.
// The statistics are updated only at samples that bring a measurement (k counts those). Between
// two measurements the filter may predict several times (a camera slower than the odometry):
// q̂ and Q̂ are then rates per unit of the prediction's `noise_scale` (one sample; or seconds,
// when the caller passes dt), F(X̂(k−1)) and ∇F P(k−1) ∇Fᵀ are the chain of those predictions
// without q̂ and Q̂, and the terms of eq. 4.10–4.11 are divided by the elapsed Δ = Σ noise_scale.
// With one prediction of scale 1 per measurement this is the thesis's filter as printed. Any
// measurement of core/pose_measurement.h can be used: r̂ and R̂ are kept per kind (compass,
// landmark range-bearing); the compass's start at R̂(0), r̂(0) of the options, another kind's at
// its first measurement's own R and r̂ = 0. A measurement rejected by the gate changes nothing.
#include <array>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/compass_ekf_model.h"
#include "core/units.h"

namespace locbench::baselines::filters {

struct SageHusaOptions {
  // Q̂(0) = diag(6.33 mm², 6.33 mm², 2 deg²) [m², m², rad²] (§4.5).
  Vector3 initial_process_noise{mm(1.0) * mm(1.0) * 6.33, mm(1.0) * mm(1.0) * 6.33, 2.0 * deg(1.0) * deg(1.0)};
  double initial_measurement_noise = 2.0 * deg(1.0) * deg(1.0);  // R̂(0) = 2 deg² [rad²]
  Vector3 initial_process_mean = Vector3::Zero();                // q̂(0) = 0
  double initial_measurement_mean = 0.0;                         // r̂(0) = 0
  double forgetting = 0.9;                                       // b (λ) in (0, 1)
  Vector3 initial_covariance = Vector3::Zero();                  // diag P(0) = 0
  bool positive_definiteness_fix = true;                         // Zhang's fix
  // q̂ and Q̂ are updated only from intervals of at least this Δ (units of noise_scale): a rate
  // estimated from two measurements a millisecond apart is noise divided by a millisecond. 0: all.
  double min_statistics_interval = 0.0;
};
void to_json(nlohmann::json& j, const SageHusaOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, SageHusaOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const SageHusaOptions& o);

// Deng's weight d(k−1) = (1 − b)/(1 − b^k) for the k-th update, k >= 1 (eq. 4.9).
double deng_forgetting_weight(double b, int k);

struct SageHusaStep {
  CompassFilterStep filter;
  // The noise statistics after this step.
  Vector3 process_mean = Vector3::Zero();     // q̂(k)
  Matrix3 process_cov = Matrix3::Zero();      // Q̂(k)
  double measurement_mean = 0.0;              // r̂(k)
  double measurement_variance = 0.0;          // R̂(k)
  double weight = 0.0;                        // d(k−1); 0 when no update
  bool process_fix_applied = false;           // Zhang's fix changed Q̂(k)
  bool measurement_fix_applied = false;       // Zhang's fix changed R̂(k)
  bool process_cov_positive_definite = true;  // of the final Q̂(k)
  bool measurement_variance_positive = true;  // R̂(k) > 0
};

class SageHusaAekf : public PoseGaussian {
 public:
  // Throws UsageError for invalid options or wheelbase <= 0.
  SageHusaAekf(const SageHusaOptions& options, double wheelbase, const Pose2& start);

  // One encoder sample: predict with the wheel travel u; with a compass heading [rad], correct
  // and update q̂, Q̂, r̂, R̂.
  SageHusaStep step(const WheelDisplacement& u, std::optional<double> compass_heading);

  // The prediction alone, Q̂(k−1)·noise_scale (1 per sample; a step of another length passes its
  // ratio to the sample period).
  void predict(const WheelDisplacement& u, double noise_scale = 1.0);
  // The correction and the noise-statistics update with any measurement, skipped when the NIS
  // (with R̂ and r̂) exceeds the gate. Fills `stats` (may be null) like step().
  MeasurementUpdate update(const PoseMeasurement& z, double gate = kNoGate, SageHusaStep* stats = nullptr);

  int updates() const { return k_; }

 private:
  // r̂ and R̂ of one measurement kind.
  struct MeasurementNoise {
    bool started = false;
    MeasurementVector mean;
    MeasurementMatrix cov;
  };
  void record_statistics(SageHusaStep& out) const;

  SageHusaOptions options_;
  double wheelbase_;
  Vector3 q_mean_;
  Matrix3 q_cov_;
  std::array<MeasurementNoise, kMeasurementKinds> r_;
  int k_ = 0;  // measurement updates so far
  // Since the last measurement: Σ q̂·noise_scale added to the mean, ∇F P(k−1) ∇Fᵀ chained over
  // the predictions, and Δ = Σ noise_scale (0 for a second measurement at the same time, which
  // then updates R̂ only).
  Vector3 q_added_ = Vector3::Zero();
  Matrix3 fpf_;
  double elapsed_ = 0.0;
};

}  // namespace locbench::baselines::filters
