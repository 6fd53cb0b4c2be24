#include "baselines/filters/sage_husa_aekf.h"

#include <Eigen/Cholesky>
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
  v.field("min_statistics_interval", o.min_statistics_interval, "", non_negative(),
          "shortest Δ between measurements that updates q̂, Q̂");
}

void validate(const SageHusaOptions& o) { validate_fields(o, "SageHusaOptions"); }

LOCBENCH_OPTIONS_JSON(SageHusaOptions)

double deng_forgetting_weight(double b, int k) {
  if (k < 1) throw UsageError("deng_forgetting_weight: k must be >= 1");
  return (1.0 - b) / (1.0 - std::pow(b, k));
}

SageHusaAekf::SageHusaAekf(const SageHusaOptions& options, double wheelbase, const Pose2& start)
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      options_(options),
      wheelbase_(wheelbase),
      q_mean_(options.initial_process_mean),
      q_cov_(options.initial_process_noise.asDiagonal()),
      fpf_(p_) {
  validate(options);
  require_positive_wheelbase(wheelbase, "SageHusaAekf");
  MeasurementNoise& compass = r_[0];  // PoseMeasurement's first kind: CompassHeading
  compass.started = true;
  compass.mean = MeasurementVector::Constant(1, options.initial_measurement_mean);
  compass.cov = MeasurementMatrix::Constant(1, 1, options.initial_measurement_noise);
}

void SageHusaAekf::predict(const WheelDisplacement& u, double noise_scale) {
  const MotionPrediction pred = predict_motion(x_, u, wheelbase_);  // F(X̂(k−1)), ∇F
  fpf_ = pred.jacobian * fpf_ * pred.jacobian.transpose();          // ∇F P(k−1) ∇Fᵀ, chained
  const Matrix3 fpf_step = pred.jacobian * p_ * pred.jacobian.transpose();
  const Vector3 q_step = noise_scale == 1.0 ? q_mean_ : Vector3(noise_scale * q_mean_);
  x_ = pred.mean + q_step;  // X̂(k/k−1)
  x_(2) = wrap_angle(x_(2));
  q_added_ += q_step;
  p_ = symmetrize(fpf_step + (noise_scale == 1.0 ? q_cov_ : Matrix3(noise_scale * q_cov_)));  // P(k/k−1)
  elapsed_ += noise_scale;
}

MeasurementUpdate SageHusaAekf::update(const PoseMeasurement& z, double gate, SageHusaStep* stats) {
  MeasurementNoise& noise = r_[z.index()];
  const LinearizedMeasurement m = linearize(z, x_);
  if (!noise.started) {
    noise.started = true;
    noise.mean = MeasurementVector::Zero(m.z.size());
    noise.cov = m.R;
  }
  const Vector3 x_pred = x_;
  const Matrix3 p_pred = p_;
  MeasurementUpdate c = measurement_innovation(m, p_pred, noise.cov, &noise.mean);
  if (c.nis > gate) {
    c.gated = true;
    return c;
  }
  apply_measurement_update(x_, p_, c, m);  // X̂(k/k), P(k)
  ++k_;
  const double d = deng_forgetting_weight(options_.forgetting, k_);

  bool process_fix = false, measurement_fix = false;
  if (elapsed_ > 0.0 && elapsed_ >= options_.min_statistics_interval) {
    // X̂(k/k) − F(X̂(k−1)) = the correction plus the q̂ the predictions added (eq. 4.10).
    Vector3 state_jump = x_ - x_pred;
    state_jump(2) = angle_diff(x_(2), x_pred(2));
    state_jump += q_added_;
    q_mean_ = (1.0 - d) * q_mean_ + (d / elapsed_) * state_jump;
    const Vector3 k_eps = c.gain * c.innovation;
    q_cov_ = symmetrize((1.0 - d) * q_cov_ + (d / elapsed_) * (k_eps * k_eps.transpose() + p_ - fpf_));  // eq. 4.11
    if (options_.positive_definiteness_fix && !is_positive_definite(q_cov_)) {                           // Zhang et al.
      q_cov_ = symmetrize(q_cov_ + (d / elapsed_) * (fpf_ - p_));
      process_fix = true;
    }
  }
  const MeasurementVector z_residual = m.residual();  // Z(k) − H X̂(k/k−1)
  noise.mean = (1.0 - d) * noise.mean + d * z_residual;
  const MeasurementMatrix hph = m.H * p_pred * m.H.transpose();  // H P(k/k−1) Hᵀ
  noise.cov = (1.0 - d) * noise.cov + d * (c.innovation * c.innovation.transpose() - hph);
  noise.cov = 0.5 * (noise.cov + noise.cov.transpose());
  if (options_.positive_definiteness_fix && noise.cov.llt().info() != Eigen::Success) {
    noise.cov += d * hph;
    measurement_fix = true;
  }
  q_added_.setZero();  // the next measurement's chain starts at this posterior
  fpf_ = p_;
  elapsed_ = 0.0;
  if (stats) {
    stats->weight = d;
    stats->process_fix_applied = process_fix;
    stats->measurement_fix_applied = measurement_fix;
  }
  return c;
}

void SageHusaAekf::record_statistics(SageHusaStep& out) const {
  const MeasurementNoise& compass = r_[0];
  out.process_mean = q_mean_;
  out.process_cov = q_cov_;
  out.measurement_mean = compass.mean(0);
  out.measurement_variance = compass.cov(0, 0);
  out.process_cov_positive_definite = is_positive_definite(q_cov_);
  out.measurement_variance_positive = compass.cov(0, 0) > 0.0;
}

SageHusaStep SageHusaAekf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  predict(u);
  SageHusaStep out;
  if (compass_heading) {
    const MeasurementUpdate c =
        update(CompassHeading{*compass_heading, options_.initial_measurement_noise}, kNoGate, &out);
    out.filter.record(x_, p_, &c);
  } else {
    out.filter.record(x_, p_, nullptr);
  }
  record_statistics(out);
  return out;
}

}  // namespace locbench::baselines::filters
