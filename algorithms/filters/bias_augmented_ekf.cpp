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

void require_valid(const MotionNoiseCorrelation& m) {
  const bool shares = (m.share.array() >= 0.0).all() && (m.share.array() < 1.0).all();
  const bool times = (m.time_s.array() > 0.0).all() && m.time_s.allFinite();
  if (!shares || !times || !(m.window_s > 0.0) || !std::isfinite(m.window_s)) {
    throw UsageError("BiasAugmentedEkf: the motion noise needs shares in [0, 1), τ > 0 and a window > 0");
  }
}

}  // namespace

BiasAugmentedEkf::BiasAugmentedEkf(double wheelbase, const Pose2& start, const Matrix3& initial_covariance,
                                   const MeasurementBiasModel& bias, const MotionNoiseCorrelation& motion)
    : wheelbase_(wheelbase), bias_(bias), motion_(motion) {
  require_positive_wheelbase(wheelbase, "BiasAugmentedEkf");
  if (!initial_covariance.allFinite()) throw UsageError("BiasAugmentedEkf: initial covariance must be finite");
  require_valid(bias.range, "range");
  require_valid(bias.bearing, "bearing");
  require_valid(motion);
  require_valid(motion.stall, "stall");
  x_.setZero();
  x_.head<3>() = to_vector(start);
  p_.setZero();
  p_.topLeftCorner<3, 3>() = symmetrize(initial_covariance);
  p_(3, 3) = bias.range.sigma * bias.range.sigma;
  p_(4, 4) = bias.bearing.sigma * bias.bearing.sigma;
  for (int j = 0; j < 3; ++j) p_(5 + j, 5 + j) = motion.share(j) > 0.0 ? 1.0 : 0.0;
  p_(8, 8) = motion.stall.sigma * motion.stall.sigma;
}

void BiasAugmentedEkf::predict(const WheelDisplacement& u, const Matrix3& body_covariance, double dt,
                               double stall_distance) {
  const MotionPrediction pred = predict_motion(x_.head<3>(), u, wheelbase_);  // eq. 4.1–4.2
  const double dt_pos = std::max(dt, 0.0);
  // The step's covariance: its white part, and the gains A of the correlated motion states.
  Matrix3 white = body_covariance;
  Vector3 gain = Vector3::Zero();
  for (int j = 0; j < 3; ++j) {
    const double s = motion_.share(j);
    if (s <= 0.0) continue;
    white(j, j) = (1.0 - s) * body_covariance(j, j);
    gain(j) = std::sqrt(std::max(0.0, s * body_covariance(j, j) * dt_pos / motion_.window_s));
  }
  const Matrix3 q = body_to_world_covariance(white, x_(2));
  const double c = std::cos(x_(2)), sn = std::sin(x_(2));
  const double stall_gain = motion_.stall.sigma > 0.0 ? -stall_distance : 0.0;
  Vector3 moved = gain.cwiseProduct(x_.segment<3>(5));  // A·m in the robot frame
  moved(0) += stall_gain * x_(8);                       // −l·D along the track
  StateMatrix f = StateMatrix::Identity();
  f.topLeftCorner<3, 3>() = pred.jacobian;
  f(0, 2) += -sn * moved(0) - c * moved(1);  // ∂(R(θ)·A·m)/∂θ
  f(1, 2) += c * moved(0) - sn * moved(1);
  f(0, 5) = c * gain(0);
  f(0, 6) = -sn * gain(1);
  f(1, 5) = sn * gain(0);
  f(1, 6) = c * gain(1);
  f(2, 7) = gain(2);
  f(0, 8) = c * stall_gain;
  f(1, 8) = sn * stall_gain;
  StateVector decay;
  decay << 1.0, 1.0, 1.0, std::exp(-dt_pos / bias_.range.time_s), std::exp(-dt_pos / bias_.bearing.time_s),
      std::exp(-dt_pos / motion_.time_s(0)), std::exp(-dt_pos / motion_.time_s(1)),
      std::exp(-dt_pos / motion_.time_s(2)), std::exp(-dt_pos / motion_.stall.time_s);
  for (int j = 3; j < kStates; ++j) f(j, j) = decay(j);
  x_.head<3>() = pred.mean;
  x_(0) += c * moved(0) - sn * moved(1);
  x_(1) += sn * moved(0) + c * moved(1);
  x_(2) += moved(2);
  x_.tail<6>() = x_.tail<6>().cwiseProduct(decay.tail<6>());
  // lazy products: Eigen sends fixed 9×9 products to its blocked GEMM, which costs more here
  const StateMatrix fp = f.lazyProduct(p_);
  StateMatrix p = fp.lazyProduct(f.transpose());
  p.topLeftCorner<3, 3>() += q;
  p(3, 3) += bias_.range.sigma * bias_.range.sigma * (1.0 - decay(3) * decay(3));
  p(4, 4) += bias_.bearing.sigma * bias_.bearing.sigma * (1.0 - decay(4) * decay(4));
  for (int j = 5; j < 8; ++j) {
    if (motion_.share(j - 5) > 0.0) p(j, j) += 1.0 - decay(j) * decay(j);
  }
  p(8, 8) += motion_.stall.sigma * motion_.stall.sigma * (1.0 - decay(8) * decay(8));
  p_ = 0.5 * (p + p.transpose());
}

BiasAugmentedEkf::Linearized BiasAugmentedEkf::linearize_full(const PoseMeasurement& z) const {
  Linearized l{linearize(z, x_.head<3>()), {}, {}};
  const Eigen::Index m = l.pose.z.size();
  l.offset.setZero(m);
  l.H.setZero(m, kStates);
  l.H.leftCols<3>() = l.pose.H;
  if (std::holds_alternative<LandmarkRangeBearing>(z)) {
    l.offset << x_(3), x_(4);
    l.H(0, 3) = 1.0;
    l.H(1, 4) = 1.0;
  }
  return l;
}

MeasurementUpdate BiasAugmentedEkf::innovation(const PoseMeasurement& z) const {
  const Linearized l = linearize_full(z);
  MeasurementUpdate u;
  u.innovation = l.pose.residual(&l.offset);
  u.innovation_covariance = l.H * p_ * l.H.transpose() + l.pose.R;
  return u;
}

double BiasAugmentedEkf::nis(const PoseMeasurement& z) const {
  const MeasurementUpdate u = innovation(z);
  const double nis = u.innovation.dot(Eigen::LDLT<MeasurementMatrix>(u.innovation_covariance).solve(u.innovation));
  return std::isfinite(nis) ? nis : std::numeric_limits<double>::infinity();
}

MeasurementUpdate BiasAugmentedEkf::update(const PoseMeasurement& z, double gate) {
  const Linearized l = linearize_full(z);
  MeasurementUpdate u;
  u.innovation = l.pose.residual(&l.offset);
  const Eigen::Matrix<double, kStates, Eigen::Dynamic, 0, kStates, 2> ph = p_ * l.H.transpose();  // P Hᵀ
  u.innovation_covariance = l.H * ph + l.pose.R;
  const Eigen::LDLT<MeasurementMatrix> ldlt(u.innovation_covariance);
  const Eigen::Matrix<double, kStates, Eigen::Dynamic, 0, kStates, 2> k = ldlt.solve(ph.transpose()).transpose();
  u.gain = k.topRows<3>();
  u.nis = u.innovation.dot(ldlt.solve(u.innovation));
  if (!std::isfinite(u.nis)) u.nis = std::numeric_limits<double>::infinity();
  if (u.nis > gate) {
    u.gated = true;
    return u;
  }
  x_ += k * u.innovation;
  x_(2) = wrap_angle(x_(2));
  const StateMatrix p = p_ - k * (l.H * p_);  // (I − K H) P
  p_ = 0.5 * (p + p.transpose());
  return u;
}

}  // namespace locbench::filters
