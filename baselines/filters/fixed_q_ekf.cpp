#include "baselines/filters/fixed_q_ekf.h"

#include <cmath>

#include "core/errors.h"
#include "core/json_options.h"

namespace locbench {
namespace {

void validate(const FixedQEkfOptions& o) {
  if (!(o.process_noise.array() >= 0.0).all()) {
    throw UsageError("FixedQEkfOptions: process_noise must be >= 0");
  }
  if (!(o.compass_variance > 0.0))
    throw UsageError("FixedQEkfOptions: compass_variance must be > 0");
  if (!(o.initial_covariance.array() >= 0.0).all()) {
    throw UsageError("FixedQEkfOptions: initial_covariance must be >= 0");
  }
}

}  // namespace

void to_json(nlohmann::json& j, const FixedQEkfOptions& o) {
  j = {{"process_noise", vector3_json(o.process_noise)},
       {"compass_variance", o.compass_variance},
       {"initial_covariance", vector3_json(o.initial_covariance)}};
}

void from_json(const nlohmann::json& j, FixedQEkfOptions& o) {
  StrictJsonReader r(j, "FixedQEkfOptions");
  r.read("process_noise", o.process_noise);
  r.read("compass_variance", o.compass_variance);
  r.read("initial_covariance", o.initial_covariance);
  r.finish();
  validate(o);
}

FixedQEkf::FixedQEkf(const FixedQEkfOptions& options, double wheelbase, const Pose2& start)
    : q_(options.process_noise.asDiagonal()),
      r_(options.compass_variance),
      wheelbase_(wheelbase),
      x_(to_vector(start)),
      p_(options.initial_covariance.asDiagonal()) {
  validate(options);
  require_positive_wheelbase(wheelbase, "FixedQEkf");
}

CompassFilterStep FixedQEkf::step(const WheelDisplacement& u,
                                  std::optional<double> compass_heading) {
  return compass_ekf_step(x_, p_, u, wheelbase_, q_, compass_heading, r_);
}

}  // namespace locbench
