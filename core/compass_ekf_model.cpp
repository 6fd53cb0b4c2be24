#include "core/compass_ekf_model.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace locbench {

bool is_positive_definite(const Matrix3& m) {
  Eigen::LLT<Matrix3> llt(m);
  return llt.info() == Eigen::Success;
}

MotionPrediction predict_motion(const Vector3& x, const WheelDisplacement& u, double wheelbase) {
  const Pose2 p = to_pose(x);
  return {to_vector(odometry_step(p, u, wheelbase)), odometry_jacobian_pose(p, u, wheelbase)};
}

void ekf_predict(Vector3& x, Matrix3& p, const WheelDisplacement& u, double wheelbase, const Matrix3& q) {
  const MotionPrediction pred = predict_motion(x, u, wheelbase);
  x = pred.mean;
  p = symmetrize(pred.jacobian * p * pred.jacobian.transpose() + q);
}

MeasurementUpdate measurement_innovation(const LinearizedMeasurement& m, const Matrix3& p, const MeasurementMatrix& r,
                                         const MeasurementVector* r_mean) {
  MeasurementUpdate u;
  u.innovation = m.residual(r_mean);
  const MeasurementGain ph = p * m.H.transpose();  // P Hᵀ
  u.innovation_covariance = m.H * ph + r;
  const Eigen::LDLT<MeasurementMatrix> ldlt(u.innovation_covariance);
  u.gain = ldlt.solve(ph.transpose()).transpose();
  u.nis = u.innovation.dot(ldlt.solve(u.innovation));
  if (!std::isfinite(u.nis)) u.nis = std::numeric_limits<double>::infinity();
  return u;
}

void apply_measurement_update(Vector3& x, Matrix3& p, const MeasurementUpdate& u, const LinearizedMeasurement& m) {
  x += u.gain * u.innovation;
  x(2) = wrap_angle(x(2));
  const Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 2, 3> h_p = m.H * p;  // H P
  p -= u.gain * h_p;
  p = symmetrize(p);
}

MeasurementUpdate ekf_update(Vector3& x, Matrix3& p, const PoseMeasurement& z, double gate) {
  const LinearizedMeasurement m = linearize(z, x);
  MeasurementUpdate u = measurement_innovation(m, p, m.R);
  if (u.nis > gate) {
    u.gated = true;
    return u;
  }
  apply_measurement_update(x, p, u, m);
  return u;
}

}  // namespace locbench
