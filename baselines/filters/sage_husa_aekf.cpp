#include "baselines/filters/sage_husa_aekf.h"

#include <cmath>

#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::baselines::filters {

// SageHusaOptions's fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, SageHusaOptions& o) {
  v.field("initial_process_noise", o.initial_process_noise, "m², m², rad²", non_negative(), "diag Q̂(0)");
  v.field("initial_measurement_noise", o.initial_measurement_noise, "rad²", positive(), "R̂(0)");
  v.field("initial_process_mean", o.initial_process_mean, "m, m, rad", any_finite(), "q̂(0)");
  v.field("initial_measurement_mean", o.initial_measurement_mean, "rad", any_finite(), "r̂(0)");
  v.field("forgetting", o.forgetting, "", open(0.0, 1.0), "b (λ), Deng's forgetting");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
  v.flag("positive_definiteness_fix", o.positive_definiteness_fix, "Zhang's fix");
}

void validate(const SageHusaOptions& o) { validate_fields(o, "SageHusaOptions"); }

LOCBENCH_OPTIONS_JSON(SageHusaOptions)

double deng_forgetting_weight(double b, int k) {
  if (k < 1) throw UsageError("deng_forgetting_weight: k must be >= 1");
  return (1.0 - b) / (1.0 - std::pow(b, k));
}

SageHusaAekf::SageHusaAekf(const SageHusaOptions& options, double wheelbase, const Pose2& start)
    : options_(options),
      wheelbase_(wheelbase),
      x_(to_vector(start)),
      p_(options.initial_covariance.asDiagonal()),
      q_mean_(options.initial_process_mean),
      q_cov_(options.initial_process_noise.asDiagonal()),
      r_mean_(options.initial_measurement_mean),
      r_var_(options.initial_measurement_noise) {
  validate(options);
  require_positive_wheelbase(wheelbase, "SageHusaAekf");
}

SageHusaStep SageHusaAekf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  const MotionPrediction pred = predict_motion(x_, u, wheelbase_);     // F(X̂(k−1)), ∇F
  const Matrix3 fpf = pred.jacobian * p_ * pred.jacobian.transpose();  // ∇F P(k−1) ∇Fᵀ
  Vector3 x_pred = pred.mean + q_mean_;                                // X̂(k/k−1)
  x_pred(2) = wrap_angle(x_pred(2));
  const Matrix3 p_pred = symmetrize(fpf + q_cov_);  // P(k/k−1)

  SageHusaStep out;
  if (!compass_heading) {
    x_ = x_pred;
    p_ = p_pred;
    out.filter.record(x_, p_, nullptr);
  } else {
    const CompassInnovation c = compass_innovation(x_pred, p_pred, *compass_heading, r_var_, r_mean_);
    x_ = x_pred;
    p_ = p_pred;
    apply_compass_update(x_, p_, c);  // X̂(k/k), P(k)
    ++k_;
    const double d = deng_forgetting_weight(options_.forgetting, k_);
    out.weight = d;

    Vector3 state_jump = x_ - pred.mean;  // X̂(k/k) − F(X̂(k−1))
    state_jump(2) = angle_diff(x_(2), pred.mean(2));
    q_mean_ = (1.0 - d) * q_mean_ + d * state_jump;
    const Vector3 k_eps = c.gain * c.innovation;
    q_cov_ = symmetrize((1.0 - d) * q_cov_ + d * (k_eps * k_eps.transpose() + p_ - fpf));
    const double z_residual = angle_diff(*compass_heading, x_pred(2));  // Z(k) − H X̂(k/k−1)
    r_mean_ = (1.0 - d) * r_mean_ + d * z_residual;
    r_var_ = (1.0 - d) * r_var_ + d * (c.innovation * c.innovation - p_pred(2, 2));

    if (options_.positive_definiteness_fix) {  // Zhang et al.
      if (!is_positive_definite(q_cov_)) {
        q_cov_ = symmetrize(q_cov_ + d * (fpf - p_));
        out.process_fix_applied = true;
      }
      if (!(r_var_ > 0.0)) {
        r_var_ += d * p_pred(2, 2);
        out.measurement_fix_applied = true;
      }
    }
    out.filter.record(x_, p_, &c);
  }
  out.process_mean = q_mean_;
  out.process_cov = q_cov_;
  out.measurement_mean = r_mean_;
  out.measurement_variance = r_var_;
  out.process_cov_positive_definite = is_positive_definite(q_cov_);
  out.measurement_variance_positive = r_var_ > 0.0;
  return out;
}

}  // namespace locbench::baselines::filters
