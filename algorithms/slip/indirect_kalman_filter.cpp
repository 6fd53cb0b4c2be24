#include "algorithms/slip/indirect_kalman_filter.h"

#include <Eigen/LU>
#include <cmath>

#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::slip {
using locbench::calibration::analyze_identifiability, locbench::calibration::IdentifiabilityReport;

// IndirectKfOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, IndirectKfOptions& o) {
  v.field("initial_covariance", o.initial_covariance, "m², m², rad², 1, 1, m²", non_negative(),
          "diag P(0) for [δx, δy, δθ, S_R, S_L, δB]");
  v.field("process_noise", o.process_noise, "m², m², rad², 1, 1, m²", non_negative(), "diag Q per sample");
  v.field("heading_variance", o.heading_variance, "rad²", positive(), "compass variance");
}

void validate(const IndirectKfOptions& o) { validate_fields(o, "IndirectKfOptions"); }

LOCBENCH_OPTIONS_JSON(IndirectKfOptions)

Matrix6 ikf_transition(const WheelDisplacement& u, double theta, double b) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double mean_u = 0.5 * (u.right + u.left);
  Matrix6 f = Matrix6::Identity();
  f(0, 2) = -s * mean_u;  // (3.20)
  f(0, 3) = c * u.right / 2.0;
  f(0, 4) = c * u.left / 2.0;
  f(1, 2) = c * mean_u;  // (3.21)
  f(1, 3) = s * u.right / 2.0;
  f(1, 4) = s * u.left / 2.0;
  f(2, 3) = u.right / b;  // (3.22)
  f(2, 4) = -u.left / b;
  f(2, 5) = (u.left - u.right) / (b * b);
  return f;
}

IndirectKalmanFilter::IndirectKalmanFilter(const IndirectKfOptions& options, double wheelbase)
    : options_(options), wheelbase_(wheelbase) {
  validate(options_);
  require_positive_wheelbase(wheelbase_, "IndirectKalmanFilter");
  p_ = options_.initial_covariance.asDiagonal();
}

void IndirectKalmanFilter::predict(const WheelDisplacement& u, double odometry_heading) {
  const Matrix6 f = ikf_transition(u, odometry_heading, wheelbase_);
  x_ = f * x_;
  p_ = f * p_ * f.transpose();
  p_.diagonal() += options_.process_noise;
  p_ = 0.5 * (p_ + p_.transpose());
}

IkfUpdate IndirectKalmanFilter::update_heading(double z) {
  IkfUpdate r;
  r.innovation = wrap_angle(z - x_(2));
  r.innovation_variance = p_(2, 2) + options_.heading_variance;
  const Vector6 k = p_.col(2) / r.innovation_variance;
  x_ += k * r.innovation;
  const Eigen::Matrix<double, 1, 6> hp = p_.row(2);
  p_ -= k * hp;
  p_ = 0.5 * (p_ + p_.transpose());
  return r;
}

void IndirectKalmanFilter::update_position(const Eigen::Vector2d& z, double variance) {
  if (!(variance > 0.0)) throw UsageError("IndirectKalmanFilter: position variance must be > 0");
  Eigen::Matrix<double, 2, 6> h = Eigen::Matrix<double, 2, 6>::Zero();
  h(0, 0) = h(1, 1) = 1.0;
  const Eigen::Matrix2d s = h * p_ * h.transpose() + variance * Eigen::Matrix2d::Identity();
  const Eigen::Matrix<double, 6, 2> k = p_ * h.transpose() * s.inverse();
  x_ += k * (z - h * x_);
  p_ = (Matrix6::Identity() - k * h) * p_;
  p_ = 0.5 * (p_ + p_.transpose());
}

void IndirectKalmanFilter::start_run() {
  x_.head<3>().setZero();
  p_.block<3, 6>(0, 0).setZero();
  p_.block<6, 3>(0, 0).setZero();
  p_.block<3, 3>(0, 0) = options_.initial_covariance.head<3>().asDiagonal();
}

IkfRunResult run_indirect_kf(std::span<const IkfRun> runs, const IndirectKfOptions& options, double wheelbase) {
  IndirectKalmanFilter f(options, wheelbase);
  IkfRunResult r;
  for (const IkfRun& run : runs) {
    f.start_run();
    double theta = run.start_heading;  // odometry heading
    for (const IkfSample& s : run.samples) {
      f.predict(s.u, theta);
      theta = wrap_angle(theta + (s.u.right - s.u.left) / wheelbase);
      if (s.reference_heading) {
        f.update_heading(angle_diff(*s.reference_heading, theta));
        ++r.heading_updates;
      }
    }
    if (run.end_position_error) f.update_position(*run.end_position_error, run.end_position_variance);
  }
  r.state = f.state();
  r.covariance = f.covariance();
  r.s_right = f.s_right();
  r.s_left = f.s_left();
  r.delta_b = f.delta_b();
  return r;
}

IkfRunResult run_indirect_kf(std::span<const IkfSample> samples, double start_heading, const IndirectKfOptions& options,
                             double wheelbase, const std::optional<Eigen::Vector2d>& end_position_error,
                             double end_position_variance) {
  const IkfRun run{{samples.begin(), samples.end()}, start_heading, end_position_error, end_position_variance};
  return run_indirect_kf(std::span<const IkfRun>(&run, 1), options, wheelbase);
}

IdentifiabilityReport ikf_identifiability(std::span<const IkfSample> samples, double start_heading, double wheelbase,
                                          double heading_variance, const Eigen::Vector3d& values,
                                          std::optional<double> end_position_variance, double relative_tolerance) {
  // Φ = ∂[δx, δy, δθ]/∂[S_R, S_L, δB], propagated with the F blocks from Φ(0) = 0.
  Eigen::Matrix3d phi = Eigen::Matrix3d::Zero();
  std::vector<Eigen::RowVector3d> rows;
  std::vector<double> variances;
  double theta = start_heading;
  for (const IkfSample& s : samples) {
    const Matrix6 f = ikf_transition(s.u, theta, wheelbase);
    phi = f.block<3, 3>(0, 0) * phi + f.block<3, 3>(0, 3);
    theta = wrap_angle(theta + (s.u.right - s.u.left) / wheelbase);
    if (s.reference_heading) {
      rows.push_back(phi.row(2));
      variances.push_back(heading_variance);
    }
  }
  if (end_position_variance) {
    rows.push_back(phi.row(0));
    rows.push_back(phi.row(1));
    variances.push_back(*end_position_variance);
    variances.push_back(*end_position_variance);
  }
  const auto m = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd j(m, 3);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    j.row(i) = rows[static_cast<std::size_t>(i)];
    cov(i, i) = variances[static_cast<std::size_t>(i)];
  }
  return analyze_identifiability(j, cov, {"S_R", "S_L", "dB"}, values, relative_tolerance);
}

}  // namespace locbench::slip
