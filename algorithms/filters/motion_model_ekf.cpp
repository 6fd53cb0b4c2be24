#include "algorithms/filters/motion_model_ekf.h"

#include <cmath>

#include "core/errors.h"

namespace locbench::filters {

Matrix3 body_to_world_covariance(const Matrix3& body, double theta) {
  Matrix3 g = Matrix3::Identity();
  const double c = std::cos(theta), s = std::sin(theta);
  g(0, 0) = c;
  g(0, 1) = -s;
  g(1, 0) = s;
  g(1, 1) = c;
  return g * body * g.transpose();
}

MotionModelEkf::MotionModelEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance)
    : PoseGaussian(to_vector(start), symmetrize(initial_covariance)), wheelbase_(wheelbase) {
  require_positive_wheelbase(wheelbase, "MotionModelEkf");
  if (!p_.allFinite()) throw UsageError("MotionModelEkf: initial covariance must be finite");
}

void MotionModelEkf::predict(const WheelDisplacement& u, const Matrix3& body_covariance) {
  ekf_predict(x_, p_, u, wheelbase_, body_to_world_covariance(body_covariance, x_(2)));
}

MeasurementUpdate MotionModelEkf::update(const PoseMeasurement& z, double gate) { return ekf_update(x_, p_, z, gate); }

}  // namespace locbench::filters
