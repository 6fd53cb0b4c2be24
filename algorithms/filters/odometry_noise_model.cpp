#include "algorithms/filters/odometry_noise_model.h"

#include <cmath>

#include "core/json_options.h"

namespace locbench {

void to_json(nlohmann::json& j, const OdometryNoiseOptions& o) {
  j = {{"k_left", o.k_left},
       {"k_right", o.k_right},
       {"sigma_left", o.sigma_left},
       {"sigma_right", o.sigma_right},
       {"form", o.form == OdometryNoiseForm::kThesis ? "thesis" : "jacobian"}};
}

void from_json(const nlohmann::json& j, OdometryNoiseOptions& o) {
  StrictJsonReader r(j, "OdometryNoiseOptions");
  r.read("k_left", o.k_left);
  r.read("k_right", o.k_right);
  r.read("sigma_left", o.sigma_left);
  r.read("sigma_right", o.sigma_right);
  std::string form = o.form == OdometryNoiseForm::kThesis ? "thesis" : "jacobian";
  r.read("form", form);
  if (form != "thesis" && form != "jacobian") {
    r.fail("form", "expected \"thesis\" or \"jacobian\"");
  }
  o.form = form == "thesis" ? OdometryNoiseForm::kThesis : OdometryNoiseForm::kJacobian;
  r.finish();
  if (o.k_left < 0.0 || o.k_right < 0.0 || o.sigma_left < 0.0 || o.sigma_right < 0.0) {
    r.fail("", "k and sigma must be >= 0");
  }
}

WheelNoiseVariance wheel_noise_variance(const OdometryNoiseOptions& o, const WheelDisplacement& u) {
  return {o.k_left * o.k_left * std::abs(u.left) + o.sigma_left * o.sigma_left,
          o.k_right * o.k_right * std::abs(u.right) + o.sigma_right * o.sigma_right};
}

IncrementNoise increment_noise(const OdometryNoiseOptions& o, const WheelDisplacement& u,
                               double wheelbase) {
  const WheelNoiseVariance w = wheel_noise_variance(o, u);
  const double sum = w.left + w.right;
  return {sum / 4.0, sum / (wheelbase * wheelbase)};  // eq. 4.36, 4.37
}

Matrix3 adaptive_process_noise(const OdometryNoiseOptions& o, double theta_prev,
                               const WheelDisplacement& u, double wheelbase) {
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

}  // namespace locbench
