#include "algorithms/filters/bias_augmented_ekf.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "algorithms/filters/motion_model_ekf.h"
#include "core/errors.h"

namespace locbench::filters {
namespace {

void require_valid(const GaussMarkovBias& b, const char* name) {
  if (!(b.sigma >= 0.0) || !std::isfinite(b.sigma) || !(b.time_s > 0.0) || !std::isfinite(b.time_s)) {
    throw UsageError(std::string("BiasAugmentedEkf: the ") + name + " bias needs σ >= 0 and τ > 0");
  }
}

}  // namespace

BiasAugmentedEkf::BiasAugmentedEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance,
                                   const MeasurementBiasModel& bias)
    : wheelbase_(wheelbase), bias_(bias) {
  require_positive_wheelbase(wheelbase, "BiasAugmentedEkf");
  if (!initial_covariance.allFinite()) throw UsageError("BiasAugmentedEkf: initial covariance must be finite");
  require_valid(bias.range, "range");
  require_valid(bias.bearing, "bearing");
  x_.setZero();
  x_.head<3>() = to_vector(start);
  p_.setZero();
  p_.topLeftCorner<3, 3>() = symmetrize(initial_covariance);
  p_(3, 3) = bias.range.sigma * bias.range.sigma;
  p_(4, 4) = bias.bearing.sigma * bias.bearing.sigma;
}

void BiasAugmentedEkf::predict(const WheelDisplacement& u, const Matrix3& body_covariance, double dt) {
  const MotionPrediction pred = predict_motion(x_.head<3>(), u, wheelbase_);  // eq. 4.1–4.2
  const Matrix3 q = body_to_world_covariance(body_covariance, x_(2));
  const double dt_pos = std::max(dt, 0.0);
  const double ar = std::exp(-dt_pos / bias_.range.time_s), ab = std::exp(-dt_pos / bias_.bearing.time_s);
  Matrix5 f = Matrix5::Identity();
  f.topLeftCorner<3, 3>() = pred.jacobian;
  f(3, 3) = ar;
  f(4, 4) = ab;
  x_.head<3>() = pred.mean;
  x_(3) *= ar;
  x_(4) *= ab;
  Matrix5 p = f * p_ * f.transpose();
  p.topLeftCorner<3, 3>() += q;
  p(3, 3) += bias_.range.sigma * bias_.range.sigma * (1.0 - ar * ar);
  p(4, 4) += bias_.bearing.sigma * bias_.bearing.sigma * (1.0 - ab * ab);
  p_ = 0.5 * (p + p.transpose());
}

BiasAugmentedEkf::Linearized BiasAugmentedEkf::linearize_full(const PoseMeasurement& z) const {
  Linearized l{linearize(z, x_.head<3>()), {}, {}};
  const Eigen::Index m = l.pose.z.size();
  l.offset.setZero(m);
  l.H.setZero(m, 5);
  l.H.leftCols<3>() = l.pose.H;
  if (std::holds_alternative<LandmarkRangeBearing>(z)) {
    l.offset << x_(3), x_(4);
    l.H(0, 3) = 1.0;
    l.H(1, 4) = 1.0;
  }
  return l;
}

double BiasAugmentedEkf::nis(const PoseMeasurement& z) const {
  const Linearized l = linearize_full(z);
  const MeasurementVector v = l.pose.residual(&l.offset);
  const MeasurementMatrix s = l.H * p_ * l.H.transpose() + l.pose.R;
  const double nis = v.dot(Eigen::LDLT<MeasurementMatrix>(s).solve(v));
  return std::isfinite(nis) ? nis : std::numeric_limits<double>::infinity();
}

MeasurementUpdate BiasAugmentedEkf::update(const PoseMeasurement& z, double gate) {
  const Linearized l = linearize_full(z);
  MeasurementUpdate u;
  u.innovation = l.pose.residual(&l.offset);
  const Eigen::Matrix<double, 5, Eigen::Dynamic, 0, 5, 2> ph = p_ * l.H.transpose();  // P Hᵀ
  u.innovation_covariance = l.H * ph + l.pose.R;
  const Eigen::LDLT<MeasurementMatrix> ldlt(u.innovation_covariance);
  const Eigen::Matrix<double, 5, Eigen::Dynamic, 0, 5, 2> k = ldlt.solve(ph.transpose()).transpose();
  u.gain = k.topRows<3>();
  u.nis = u.innovation.dot(ldlt.solve(u.innovation));
  if (!std::isfinite(u.nis)) u.nis = std::numeric_limits<double>::infinity();
  if (u.nis > gate) {
    u.gated = true;
    return u;
  }
  x_ += k * u.innovation;
  x_(2) = wrap_angle(x_(2));
  const Matrix5 p = p_ - k * (l.H * p_);  // (I − K H) P
  p_ = 0.5 * (p + p.transpose());
  return u;
}

}  // namespace locbench::filters
