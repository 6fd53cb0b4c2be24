#include "baselines/filters/vb_akf.h"

#include <cmath>

#include "core/errors.h"
#include "core/json_options.h"

namespace locbench {
namespace {

void validate(const VbAkfOptions& o) {
  if (!(o.process_noise.array() >= 0.0).all()) {
    throw UsageError("VbAkfOptions: process_noise must be >= 0");
  }
  if (!(o.initial_measurement_variance > 0.0)) {
    throw UsageError("VbAkfOptions: initial_measurement_variance must be > 0");
  }
  if (!(o.initial_shape > 0.0)) throw UsageError("VbAkfOptions: initial_shape must be > 0");
  if (!(o.forgetting > 0.0 && o.forgetting <= 1.0)) {
    throw UsageError("VbAkfOptions: forgetting must be in (0, 1]");
  }
  if (o.iterations < 1) throw UsageError("VbAkfOptions: iterations must be >= 1");
  if (!(o.initial_covariance.array() >= 0.0).all()) {
    throw UsageError("VbAkfOptions: initial_covariance must be >= 0");
  }
}

}  // namespace

void to_json(nlohmann::json& j, const VbAkfOptions& o) {
  j = {{"process_noise", vector3_json(o.process_noise)},
       {"initial_measurement_variance", o.initial_measurement_variance},
       {"initial_shape", o.initial_shape},
       {"forgetting", o.forgetting},
       {"iterations", o.iterations},
       {"initial_covariance", vector3_json(o.initial_covariance)}};
}

void from_json(const nlohmann::json& j, VbAkfOptions& o) {
  StrictJsonReader r(j, "VbAkfOptions");
  r.read("process_noise", o.process_noise);
  r.read("initial_measurement_variance", o.initial_measurement_variance);
  r.read("initial_shape", o.initial_shape);
  r.read("forgetting", o.forgetting);
  r.read("iterations", o.iterations);
  r.read("initial_covariance", o.initial_covariance);
  r.finish();
  validate(o);
}

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

}  // namespace locbench
