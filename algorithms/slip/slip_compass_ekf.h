#pragma once
// The two EKFs of §3.6.1 on a sequence of samples, built on the 3-state CompassEkf
// (algorithms/filters, eq. 3.27–3.28) with the published fixed Q = diag(6.33 mm², 6.33 mm²,
// 2 deg²) and R = 2 deg²:
// - "first EKF" (correct_slip = false): ΔD, Δθ from the encoders (3.12–3.13) and the
//   pseudo-measurement Z = θ̂(k−1) + θ_E(k) — its innovation is zero, so it is dead reckoning;
// - "second EKF" (correct_slip = true): slip detection and correction (slip_detector.h), Z = the
//   compass heading, or θ̂(k−1) + θ_E(k) while the compass is disturbed (§3.6 rule 1).
// Extensions (ours, off by default):
// - latch_disturbance: rule 3 only fires at the sample where a disturbance starts or ends (a
//   zone adds a constant bias, so the increments inside look normal while the absolute heading
//   is wrong). With the latch, the unexplained jumps θ_C − θ_E of the flagged samples are summed
//   and the compass stays "disturbed" while |sum| > latch_tolerance.
// - gyro fallback (§3.6.1's suggestion): while the compass is disturbed, a gyro increment θ_G
//   takes θ_C's place in the slip rule (with the gyro's own μ, σ) and Z = θ̂(k−1) + θ_G(k).
#include <optional>
#include <span>
#include <vector>

#include "algorithms/slip/slip_detector.h"
#include "core/compass_ekf_model.h"

namespace locbench::slip {

struct SlipSample {
  WheelDisplacement u;                   // encoder wheel travel of the sample [m]
  std::optional<double> compass;         // absolute compass heading at its end [rad]
  std::optional<double> gyro_increment;  // heading increment from a gyro [rad]
};

enum class HeadingSource { kNone, kCompass, kPseudoEncoder, kPseudoGyro };

struct SlipEkfOptions {
  bool correct_slip = true;
  SlipDetectorOptions detector;
  bool latch_disturbance = false;
  double latch_tolerance = deg(5.0);  // [rad]
  bool gyro_fallback = false;
  // Fixed Q (§3.6.1 "Q(k) = diag[6.33, 6.33, 2]", taken as mm², mm², deg² per sample) [SI].
  Vector3 process_noise{mm(1.0) * mm(1.0) * 6.33, mm(1.0) * mm(1.0) * 6.33, 2.0 * deg(1.0) * deg(1.0)};
  double compass_variance = 2.0 * deg(1.0) * deg(1.0);  // R = 2 deg² [rad²]
  Vector3 initial_covariance = Vector3::Zero();         // P(0) = 0 (known start)
};

struct SlipEkfStep {
  SlipDecision decision;       // status kNoSlip with θ_C = 0 when no increment was available
  bool had_increment = false;  // a reference increment (compass or gyro) was available
  bool compass_disturbed = false;
  HeadingSource source = HeadingSource::kNone;
  Vector3 mean = Vector3::Zero();
};

struct SlipEkfRun {
  std::vector<SlipEkfStep> steps;
  Pose2 final_pose;
  std::size_t slips_detected = 0;
  std::size_t disturbed_samples = 0;
};

// `initial_compass`: the compass reading at the start pose (for the first increment).
// `gyro_model`: μ, σ of θ_E − θ_G (needed when options.gyro_fallback). Throws UsageError for
// invalid options or wheelbase ≤ 0.
SlipEkfRun run_slip_ekf(std::span<const SlipSample> samples, std::optional<double> initial_compass,
                        const SlipModel& compass_model, const std::optional<SlipModel>& gyro_model,
                        const SlipEkfOptions& options, double wheelbase, const Pose2& start);

}  // namespace locbench::slip
