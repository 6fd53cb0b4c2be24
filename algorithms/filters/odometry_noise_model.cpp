#include "algorithms/filters/odometry_noise_model.h"

#include <cmath>

#include "core/enum_names.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::filters {

constexpr EnumNames<OdometryNoiseForm, 2> kForms{
    {{OdometryNoiseForm::kThesis, "thesis"}, {OdometryNoiseForm::kJacobian, "jacobian"}}};

const char* to_string(OdometryNoiseForm f) { return enum_name(kForms, f); }
OdometryNoiseForm odometry_noise_form_from_string(const std::string& s) { return enum_value(kForms, s, "expected"); }

// OdometryNoiseOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, OdometryNoiseOptions& o) {
  v.field("k_left", o.k_left, "√m", non_negative(), "k_l (§4.5)");
  v.field("k_right", o.k_right, "√m", non_negative(), "k_r");
  v.field("sigma_left", o.sigma_left, "m", non_negative(), "σ_l");
  v.field("sigma_right", o.sigma_right, "m", non_negative(), "σ_r");
  v.choice("form", o.form, to_string, odometry_noise_form_from_string, "\"thesis\" or \"jacobian\"");
}

void validate(const OdometryNoiseOptions& o) { validate_fields(o, "OdometryNoiseOptions"); }

LOCBENCH_OPTIONS_JSON(OdometryNoiseOptions)

WheelNoiseVariance wheel_noise_variance(const OdometryNoiseOptions& o, const WheelDisplacement& u) {
  return {o.k_left * o.k_left * std::abs(u.left) + o.sigma_left * o.sigma_left,
          o.k_right * o.k_right * std::abs(u.right) + o.sigma_right * o.sigma_right};
}

IncrementNoise increment_noise(const OdometryNoiseOptions& o, const WheelDisplacement& u, double wheelbase) {
  const WheelNoiseVariance w = wheel_noise_variance(o, u);
  const double sum = w.left + w.right;
  return {sum / 4.0, sum / (wheelbase * wheelbase)};  // eq. 4.36, 4.37
}

Matrix3 adaptive_process_noise(const OdometryNoiseOptions& o, double theta_prev, const WheelDisplacement& u,
                               double wheelbase) {
  if (o.form == OdometryNoiseForm::kJacobian) {
    const WheelNoiseVariance w = wheel_noise_variance(o, u);
    const Matrix32 fu = odometry_jacobian_wheels(Pose2(0.0, 0.0, theta_prev), u, wheelbase);
    const Eigen::Vector2d var(w.right, w.left);  // columns ordered (right, left)
    return fu * var.asDiagonal() * fu.transpose();
  }
  const IncrementNoise n = increment_noise(o, u, wheelbase);
  const double mid = theta_prev + 0.5 * body_increment(u, wheelbase).rotation;
  const double c = std::cos(mid), s = std::sin(mid);
  Matrix3 q = Matrix3::Zero();
  q(0, 0) = n.distance * c * c;  // eq. 4.43
  q(1, 1) = n.distance * s * s;
  q(2, 2) = n.rotation;
  return q;
}

}  // namespace locbench::filters
