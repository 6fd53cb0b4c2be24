#include "algorithms/filters/compass_ekf.h"

#include <cmath>
#include <utility>

#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::filters {

// CompassEkfOptions's fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, CompassEkfOptions& o) {
  v.nested("noise", o.noise, "OdometryNoiseOptions");
  v.field("compass_variance", o.compass_variance, "rad²", positive(), "R (§4.5)");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
  v.field("process_noise_scale", o.process_noise_scale, "", non_negative(), "multiplies Q");
}

void validate(const CompassEkfOptions& o) { validate_fields(o, "CompassEkfOptions"); }

LOCBENCH_OPTIONS_JSON(CompassEkfOptions)

CompassEkf::CompassEkf(const CompassEkfOptions& options, double wheelbase, const Pose2& start)
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      options_(options),
      wheelbase_(wheelbase) {
  validate(options);
  require_positive_wheelbase(wheelbase, "CompassEkf");
}

CompassEkf::CompassEkf(ProcessNoiseModel process_noise, double compass_variance, const Matrix3& initial_covariance,
                       double wheelbase, const Pose2& start)
    : PoseGaussian(to_vector(start), symmetrize(initial_covariance)),
      custom_q_(std::move(process_noise)),
      wheelbase_(wheelbase) {
  options_.compass_variance = compass_variance;
  if (!custom_q_) throw UsageError("CompassEkf: empty process-noise model");
  if (!(compass_variance > 0.0)) throw UsageError("CompassEkf: compass_variance must be > 0");
  require_positive_wheelbase(wheelbase, "CompassEkf");
}

Matrix3 CompassEkf::process_noise(const WheelDisplacement& u) const {
  if (custom_q_) return custom_q_(x_, u, wheelbase_);
  return options_.process_noise_scale * adaptive_process_noise(options_.noise, x_(2), u, wheelbase_);
}

void CompassEkf::predict(const WheelDisplacement& u, double noise_scale) {
  Matrix3 q = process_noise(u);  // Q(k−1) at X̂(k−1) (eq. 4.43)
  if (noise_scale != 1.0) q *= noise_scale;
  ekf_predict(x_, p_, u, wheelbase_, q);
}

MeasurementUpdate CompassEkf::update(const PoseMeasurement& z, double gate) { return ekf_update(x_, p_, z, gate); }

CompassFilterStep CompassEkf::step(const WheelDisplacement& u, std::optional<double> compass_heading) {
  predict(u);
  CompassFilterStep out;
  if (compass_heading) {
    const MeasurementUpdate c = update(CompassHeading{*compass_heading, options_.compass_variance});
    out.record(x_, p_, &c);
  } else {
    out.record(x_, p_, nullptr);
  }
  return out;
}

}  // namespace locbench::filters
