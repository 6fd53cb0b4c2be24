#pragma once
// Wheel-slip detection and correction with an electronic compass (§3.2.3–3.4). Per sample:
//   θ_E(k) = (U_R − U_L)/B                                      (3.1, encoder increment)
//   Δθ'(k) = θ_E(k) − θ_C(k)                                     (3.2, θ_C: compass increment)
// Slip model (§3.2.3): at most one wheel slips per sample;
//   compass disturbed  ⇔ θ_C > U_R/B or θ_C < −U_L/B            (rule 3)
//   slip               ⇔ not disturbed and |Δθ' − μ|/σ > z_p    (rules 4–5; z_0.95 = 1.96)
//   which wheel: θ_C > θ_E → left slipped, θ_C < θ_E → right    (§3.3)
// Correction (§3.4):
//   left slip:  ΔD = (2U_R − B tan θ_C)/2, Δθ = θ_C              (3.14–3.15)
//   right slip: ΔD = (2U_L + B tan θ_C)/2, Δθ = θ_C              (3.16–3.17)
// μ, σ come from a calibration run: μ = mean(Δθ'), σ = √(E[Δθ'²] − μ²) (§3.2.3). Any other
// heading-increment sensor (a gyro, §3.6.1's suggested fallback) can take θ_C's place with its
// own (μ, σ). SI units (m, rad).
#include <nlohmann/json.hpp>
#include <span>

#include "core/diff_drive_odometry.h"

namespace locbench::slip {

// μ and σ of Δθ' = θ_E − θ_C [rad].
struct SlipModel {
  double mean = 0.0;
  double stddev = 0.0;
};
// μ = (1/n)ΣΔθ', σ = √((1/n)ΣΔθ'² − μ²). Throws std::invalid_argument for < 2 samples or σ = 0.
SlipModel fit_slip_model(std::span<const double> delta_theta_prime);

struct SlipDetectorOptions {
  // P{|Δθ' − μ|/σ ≤ z} under no slip; 0.95 → z = 1.96 (the thesis's best), 0.9 → 1.645 for
  // smooth floors (§3.2.3).
  double probability = 0.95;
  // Apply the compass-disturbance rule (rule 3).
  bool check_disturbance = true;
  // Widens the rule-3 interval [−U_L/B, U_R/B] by this much on each side [rad]; 0 = as
  // published. (With a 2° compass resolution a standing robot's reading may flip by one step.)
  double disturbance_margin = 0.0;
};
void to_json(nlohmann::json& j, const SlipDetectorOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, SlipDetectorOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const SlipDetectorOptions& o);

// z with P{|Z| ≤ z} = probability for a standard normal Z: Φ⁻¹((1 + p)/2).
double slip_threshold(double probability);

enum class SlipWheel { kNone, kLeft, kRight };
enum class SampleStatus { kNoSlip, kLeftSlip, kRightSlip, kCompassDisturbed };
const char* to_string(SampleStatus s);

// Rule 3: θ_C outside [min(−U_L/B, U_R/B), max(−U_L/B, U_R/B)] widened by `margin` (the
// published interval assumes forward travel; the min/max keeps it valid backwards).
bool compass_disturbed(const WheelDisplacement& u, double theta_c, double wheelbase, double margin = 0.0);
// §3.3: θ_C > θ_E → left, θ_C < θ_E → right, equal → none.
SlipWheel slipped_wheel(double theta_c, double theta_e);
// ΔD, Δθ of a sample (3.12–3.13 for kNone, 3.14–3.15 left, 3.16–3.17 right).
BodyIncrement corrected_increment(const WheelDisplacement& u, double theta_c, double wheelbase, SlipWheel wheel);
// Wheel travel that reproduces an increment exactly: U_L = ΔD − BΔθ/2, U_R = ΔD + BΔθ/2 (to
// feed filters that take wheel travel).
WheelDisplacement wheels_for(const BodyIncrement& b, double wheelbase);

struct SlipDecision {
  SampleStatus status = SampleStatus::kNoSlip;
  double theta_e = 0.0;      // θ_E [rad]
  double theta_c = 0.0;      // θ_C [rad]
  double delta_prime = 0.0;  // Δθ' [rad]
  double z_score = 0.0;      // (Δθ' − μ)/σ
  BodyIncrement increment;   // corrected ΔD, Δθ (3.12–3.17; uncorrected when disturbed)
  WheelDisplacement wheels;  // travel reproducing `increment` exactly

  bool slipped() const { return status == SampleStatus::kLeftSlip || status == SampleStatus::kRightSlip; }
};

class SlipDetector {
 public:
  // Throws UsageError for σ ≤ 0, wheelbase ≤ 0 or invalid options.
  SlipDetector(const SlipModel& model, const SlipDetectorOptions& options, double wheelbase);
  // One sample: the encoder wheel travel and the reference heading increment θ_C.
  SlipDecision classify(const WheelDisplacement& u, double theta_c) const;

  double threshold() const { return z_; }
  const SlipModel& model() const { return model_; }

 private:
  SlipModel model_;
  SlipDetectorOptions options_;
  double wheelbase_;
  double z_;
};

}  // namespace locbench::slip
