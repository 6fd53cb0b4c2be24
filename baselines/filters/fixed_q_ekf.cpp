#include "baselines/filters/fixed_q_ekf.h"

#include <cmath>

#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::baselines::filters {

// FixedQEkfOptions's fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, FixedQEkfOptions& o) {
  v.field("process_noise", o.process_noise, "m², m², rad²", non_negative(), "diag Q per step");
  v.field("compass_variance", o.compass_variance, "rad²", positive(), "R");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
}

void validate(const FixedQEkfOptions& o) { validate_fields(o, "FixedQEkfOptions"); }

LOCBENCH_OPTIONS_JSON(FixedQEkfOptions)

FixedQEkf::FixedQEkf(const FixedQEkfOptions& options, double wheelbase, const Pose2& start)
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      q_(options.process_noise.asDiagonal()),
      r_(options.compass_variance),
      wheelbase_(wheelbase) {
  validate(options);
  require_positive_wheelbase(wheelbase, "FixedQEkf");
}

void FixedQEkf::predict(const WheelDisplacement& u, double noise_scale) {
  ekf_predict(x_, p_, u, wheelbase_, noise_scale == 1.0 ? q_ : Matrix3(noise_scale * q_));
}

MeasurementUpdate FixedQEkf::update(const PoseMeasurement& z, double gate) { return ekf_update(x_, p_, z, gate); }

CompassFilterStep FixedQEkf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  predict(u);
  CompassFilterStep out;
  if (compass_heading) {
    const MeasurementUpdate c = update(CompassHeading{*compass_heading, r_});
    out.record(x_, p_, &c);
  } else {
    out.record(x_, p_, nullptr);
  }
  return out;
}

}  // namespace locbench::baselines::filters
