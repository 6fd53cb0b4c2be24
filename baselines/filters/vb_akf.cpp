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
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      q_(options.process_noise.asDiagonal()),
      rho_(options.forgetting),
      iterations_(options.iterations),
      initial_shape_(options.initial_shape),
      wheelbase_(wheelbase) {
  validate(options);
  require_positive_wheelbase(wheelbase, "VbAkf");
  NoisePosterior& compass = noise_[0];  // PoseMeasurement's first kind: CompassHeading
  compass.started = true;
  compass.alpha = options.initial_shape;
  compass.beta = MeasurementVector::Constant(1, options.initial_shape * options.initial_measurement_variance);
}

void VbAkf::predict(const WheelDisplacement& u, double noise_scale) {
  ekf_predict(x_, p_, u, wheelbase_, noise_scale == 1.0 ? q_ : Matrix3(noise_scale * q_));
  for (NoisePosterior& n : noise_) {  // heuristic dynamics of the noise parameters
    n.alpha *= rho_;
    n.beta *= rho_;
  }
}

MeasurementUpdate VbAkf::update(const PoseMeasurement& z, double gate) {
  NoisePosterior& noise = noise_[z.index()];
  const LinearizedMeasurement m = linearize(z, x_);
  if (!noise.started) {
    noise.started = true;
    noise.alpha = initial_shape_;
    noise.beta = initial_shape_ * m.R.diagonal();
  }
  const Vector3 x_pred = x_;
  const Matrix3 p_pred = p_;
  const MeasurementVector beta_pred = noise.beta;
  MeasurementUpdate c;
  if (gate < kNoGate) {
    const MeasurementMatrix r_prior = (beta_pred / noise.alpha).asDiagonal();
    c = measurement_innovation(m, p_pred, r_prior);
    if (c.nis > gate) {
      c.gated = true;
      return c;
    }
  }
  noise.alpha += 0.5;
  for (int n = 0; n < iterations_; ++n) {
    const MeasurementMatrix r = (noise.beta / noise.alpha).asDiagonal();
    c = measurement_innovation(m, p_pred, r);
    x_ = x_pred;
    p_ = p_pred;
    apply_measurement_update(x_, p_, c, m);
    const MeasurementVector residual = measurement_residual(z, x_);  // Z − h(X̂)
    const MeasurementVector hph = (m.H * p_ * m.H.transpose()).diagonal();
    noise.beta = beta_pred + 0.5 * residual.cwiseProduct(residual) + 0.5 * hph;
  }
  return c;
}

VbAkfStep VbAkf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  predict(u);
  VbAkfStep out;
  if (compass_heading) {
    const MeasurementUpdate c = update(CompassHeading{*compass_heading, measurement_variance()});
    out.filter.record(x_, p_, &c);
  } else {
    out.filter.record(x_, p_, nullptr);
  }
  const NoisePosterior& compass = noise_[0];
  out.shape = compass.alpha;
  out.scale = compass.beta(0);
  out.measurement_variance = compass.beta(0) / compass.alpha;
  return out;
}

}  // namespace locbench::baselines::filters
