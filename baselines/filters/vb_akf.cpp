#include "baselines/filters/vb_akf.h"

#include <cmath>

#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::baselines::filters {

// VbAkfOptions's fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, VbAkfOptions& o) {
  v.field("process_noise", o.process_noise, "m², m², rad²", non_negative(), "diag Q per step");
  v.field("initial_measurement_variance", o.initial_measurement_variance, "rad²", positive(), "initial R");
  v.field("initial_shape", o.initial_shape, "", positive(), "α(0)");
  v.field("forgetting", o.forgetting, "", open_closed(0.0, 1.0), "ρ");
  v.field("iterations", o.iterations, "", at_least(1), "fixed-point iterations per update");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
}

void validate(const VbAkfOptions& o) { validate_fields(o, "VbAkfOptions"); }

LOCBENCH_OPTIONS_JSON(VbAkfOptions)

VbAkf::VbAkf(const VbAkfOptions& options, double wheelbase, const Pose2& start)
    : q_(options.process_noise.asDiagonal()),
      rho_(options.forgetting),
      iterations_(options.iterations),
      wheelbase_(wheelbase),
      x_(to_vector(start)),
      p_(options.initial_covariance.asDiagonal()),
      alpha_(options.initial_shape),
      beta_(options.initial_shape * options.initial_measurement_variance) {
  validate(options);
  require_positive_wheelbase(wheelbase, "VbAkf");
}

VbAkfStep VbAkf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  const MotionPrediction pred = predict_motion(x_, u, wheelbase_);
  const Vector3 x_pred = pred.mean;
  const Matrix3 p_pred = symmetrize(pred.jacobian * p_ * pred.jacobian.transpose() + q_);
  alpha_ *= rho_;  // heuristic dynamics of the noise parameters
  beta_ *= rho_;

  VbAkfStep out;
  x_ = x_pred;
  p_ = p_pred;
  if (compass_heading) {
    const double beta_pred = beta_;
    alpha_ += 0.5;
    CompassInnovation c;
    for (int n = 0; n < iterations_; ++n) {
      c = compass_innovation(x_pred, p_pred, *compass_heading, beta_ / alpha_);
      x_ = x_pred;
      p_ = p_pred;
      apply_compass_update(x_, p_, c);
      const double residual = angle_diff(*compass_heading, x_(2));  // Z − H X̂
      beta_ = beta_pred + 0.5 * residual * residual + 0.5 * p_(2, 2);
    }
    out.filter.record(x_, p_, &c);
  } else {
    out.filter.record(x_, p_, nullptr);
  }
  out.shape = alpha_;
  out.scale = beta_;
  out.measurement_variance = beta_ / alpha_;
  return out;
}

}  // namespace locbench::baselines::filters
