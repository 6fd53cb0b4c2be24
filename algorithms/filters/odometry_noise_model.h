#pragma once
// The thesis's odometry noise model and per-sample process noise (eq. 4.22–4.44).
// Each wheel's measured travel is U = u + δ − e (eq. 4.16, 4.22): floor/slip noise
// δ ~ N(0, k²|U|) (Chong & Kleeman, k in √m) and the quantization error e, replaced by
// N(0, σ²) (eq. 4.35, see quantization_noise.h). Then
//   var(w_d) = (k_l²|U_L| + k_r²|U_R| + σ_l² + σ_r²)/4     (eq. 4.36)
//   var(w_θ) = (k_l²|U_L| + k_r²|U_R| + σ_l² + σ_r²)/B²    (eq. 4.37)
//   Q(k−1) = diag(var(w_d) cos²(θ + Δθ/2), var(w_d) sin²(θ + Δθ/2), var(w_θ))  (eq. 4.41–4.44)
// with θ = θ̂(k−1) and Δθ the measured heading increment of the sample. SI units inside.
#include <nlohmann/json.hpp>
#include <string>

#include "core/diff_drive_odometry.h"
#include "core/units.h"

namespace locbench::filters {

// kThesis is eq. 4.43–4.44 as published. kJacobian propagates the same per-wheel variances
// through the full wheel Jacobian, Q = F_u diag(var_R, var_L) F_uᵀ (core's
// odometry_jacobian_wheels): it keeps the cross terms and the lateral error ΔD·w_θ/2 that the
// diagonal form drops (the form that makes a filter consistent when the noise really is this).
enum class OdometryNoiseForm { kThesis, kJacobian };

struct OdometryNoiseOptions {
  double k_left = 0.005;   // k_l [√m] (§4.5)
  double k_right = 0.005;  // k_r [√m]
  // σ of the Gaussian stand-in of each encoder's quantization error [m]; the published 5.00 mm
  // for C = 12.64 / 12.70 mm (§4.4).
  double sigma_left = mm(5.00);
  double sigma_right = mm(5.00);
  OdometryNoiseForm form = OdometryNoiseForm::kThesis;
};
void to_json(nlohmann::json& j, const OdometryNoiseOptions& o);
// Strict: unknown keys or wrong types throw UsageError; "form" is "thesis" or "jacobian".
void from_json(const nlohmann::json& j, OdometryNoiseOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const OdometryNoiseOptions& o);
const char* to_string(OdometryNoiseForm f);  // "thesis" | "jacobian"
// The inverse; throws UsageError otherwise.
OdometryNoiseForm odometry_noise_form_from_string(const std::string& s);

// Variance of each wheel's travel error in one sample: k²|U| + σ² [m²].
struct WheelNoiseVariance {
  double left = 0.0;
  double right = 0.0;
};
WheelNoiseVariance wheel_noise_variance(const OdometryNoiseOptions& o, const WheelDisplacement& u);

// var(w_d) [m²] and var(w_θ) [rad²] (eq. 4.36–4.37).
struct IncrementNoise {
  double distance = 0.0;
  double rotation = 0.0;
};
IncrementNoise increment_noise(const OdometryNoiseOptions& o, const WheelDisplacement& u, double wheelbase);

// Q(k−1) for a step from heading theta_prev with wheel travel u (eq. 4.43–4.44, or the
// Jacobian form).
Matrix3 adaptive_process_noise(const OdometryNoiseOptions& o, double theta_prev, const WheelDisplacement& u,
                               double wheelbase);

}  // namespace locbench::filters
