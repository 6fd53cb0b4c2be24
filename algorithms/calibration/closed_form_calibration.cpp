#include "algorithms/calibration/closed_form_calibration.h"

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/angle.h"
#include "core/linear_algebra.h"

namespace locbench::calibration {
namespace {

bool is_wheel_kind(OdometryInputKind k) {
  return k == OdometryInputKind::kWheelTicks || k == OdometryInputKind::kWheelAngles;
}

// The two regressors of a sample's rotation (see the header).
Eigen::Vector2d rotation_regressors(const CalibrationData& data, const CalibrationSample& s) {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  for (const OdometryIncrement& inc : s.increments) {
    switch (data.kind) {
      case OdometryInputKind::kWheelTicks:
        a += Eigen::Vector2d(data.meters_per_tick_left * inc.first, data.meters_per_tick_right * inc.second);
        break;
      case OdometryInputKind::kWheelAngles: a += Eigen::Vector2d(inc.first, inc.second); break;
      case OdometryInputKind::kBodyIncrements: a += Eigen::Vector2d(inc.second, inc.first); break;
      case OdometryInputKind::kVelocityIntegrals: a += Eigen::Vector2d(inc.second, inc.dt); break;
    }
  }
  return a;
}

// Minimum-norm correction of x0: x0 + A⁺(y − A·x0), A⁺ by SVD with a relative cutoff.
Eigen::VectorXd min_norm_update(const Eigen::MatrixXd& A, const Eigen::VectorXd& y, const Eigen::VectorXd& x0,
                                double& condition) {
  const linalg::Svd svd = linalg::jacobi_svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singular_values;
  condition = std::numeric_limits<double>::infinity();
  if (s.size() == 0 || s(0) <= 0.0) return x0;
  const double cutoff = 1e-9 * s(0);
  const Eigen::VectorXd b = svd.u.transpose() * (y - A * x0);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(s.size());
  bool full = true;
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (s(i) > cutoff) {
      z(i) = b(i) / s(i);
    } else {
      full = false;
    }
  }
  if (full) condition = s(0) / s(s.size() - 1);
  return x0 + svd.v * z;
}

}  // namespace

ClosedFormResult closed_form_calibration(const CalibrationData& data, const ModelParameters& start,
                                         const ParameterMask& free) {
  if (data.samples.empty()) {
    throw std::invalid_argument("closed_form_calibration: no samples");
  }
  const bool wheels = is_wheel_kind(data.kind);
  const Eigen::Vector3d q0 = start.odometry;
  ClosedFormResult out;
  out.parameters = start;

  // ---- Step 1: rotation coefficients β (wheels: J21, J22; others: q1, q2).
  Eigen::Vector2d beta0 = wheels ? Eigen::Vector2d(-q0(0) / q0(2), q0(1) / q0(2)) : Eigen::Vector2d(q0(1), q0(2));
  std::array<bool, 2> beta_free =
      wheels ? std::array<bool, 2>{free[0] || free[2], free[1] || free[2]} : std::array<bool, 2>{free[1], free[2]};
  const Eigen::Index nfree = (beta_free[0] ? 1 : 0) + (beta_free[1] ? 1 : 0);
  const auto n = static_cast<Eigen::Index>(data.samples.size());
  Eigen::Vector2d beta = beta0;
  if (nfree > 0) {
    Eigen::MatrixXd A(n, nfree);
    Eigen::VectorXd y(n), x0(nfree);
    for (Eigen::Index i = 0; i < n; ++i) {
      const CalibrationSample& s = data.samples[static_cast<std::size_t>(i)];
      const Eigen::Vector2d a = rotation_regressors(data, s);
      const double predicted = a.dot(beta0);
      // Unwrap the reference rotation next to the nominal prediction (samples may turn > π).
      double yi = predicted + angle_diff(s.reference.theta, predicted);
      Eigen::Index c = 0;
      for (int j = 0; j < 2; ++j) {
        if (beta_free[static_cast<std::size_t>(j)]) {
          A(i, c++) = a(j);
        } else {
          yi -= a(j) * beta0(j);
        }
      }
      y(i) = yi;
    }
    Eigen::Index c = 0;
    for (int j = 0; j < 2; ++j) {
      if (beta_free[static_cast<std::size_t>(j)]) x0(c++) = beta0(j);
    }
    const Eigen::VectorXd x = min_norm_update(A, y, x0, out.rotation_condition);
    c = 0;
    for (int j = 0; j < 2; ++j) {
      if (beta_free[static_cast<std::size_t>(j)]) beta(j) = x(c++);
    }
  }

  // ---- Step 2: translation scale (and sensor pose).
  const Eigen::Vector3d unit =
      wheels ? Eigen::Vector3d(-beta(0), beta(1), 1.0) : Eigen::Vector3d(1.0, beta(0), beta(1));
  const bool scale_free = wheels ? free[2] : free[0];
  const bool sensor_free = data.sensor_reference && free[3] && free[4] && free[5];
  double scale = wheels ? q0(2) : q0(0);
  Pose2 sensor = start.sensor;
  if (scale_free && sensor_free) {
    Eigen::Matrix<double, 5, 5> M = Eigen::Matrix<double, 5, 5>::Zero();
    for (const CalibrationSample& s : data.samples) {
      const Pose2 o = predict_robot_displacement(data, s, unit);
      const double co = std::cos(o.theta), so = std::sin(o.theta);
      Eigen::Matrix<double, 2, 5> L;
      L << o.x, co - 1.0, -so, -s.reference.x, s.reference.y,  //
          o.y, so, co - 1.0, -s.reference.y, -s.reference.x;
      M += L.transpose() * L;
    }
    const Eigen::Matrix3d Muu = M.topLeftCorner<3, 3>();
    const Eigen::Matrix<double, 3, 2> Muv = M.topRightCorner<3, 2>();
    const Eigen::Matrix3d Muu_inv = linalg::pseudo_inverse(Muu);
    const Eigen::Matrix2d S = M.bottomRightCorner<2, 2>() - Muv.transpose() * Muu_inv * Muv;
    const linalg::SymmetricEigen2 eig = linalg::symmetric_eigen2(S);
    Eigen::Vector2d v = eig.vectors.col(0);  // smallest eigenvalue first
    Eigen::Vector3d u = -Muu_inv * Muv * v;
    if (u(0) < 0.0) {
      v = -v;
      u = -u;
    }
    scale = u(0);
    sensor = Pose2(u(1), u(2), std::atan2(v(1), v(0)));
  } else if (scale_free) {
    double num = 0.0, den = 0.0;
    for (const CalibrationSample& s : data.samples) {
      const Pose2 o = predict_robot_displacement(data, s, unit);
      const Pose2 ref = data.sensor_reference ? sensor * s.reference * sensor.inverse() : s.reference;
      num += o.x * ref.x + o.y * ref.y;
      den += o.x * o.x + o.y * o.y;
    }
    if (den > 0.0) scale = num / den;
  }

  Eigen::Vector3d q = q0;
  if (wheels) {
    q = Eigen::Vector3d(-beta(0) * scale, beta(1) * scale, scale);
  } else {
    q = Eigen::Vector3d(scale, beta(0), beta(1));
  }
  for (int j = 0; j < 3; ++j) {
    if (!free[static_cast<std::size_t>(j)]) q(j) = q0(j);
  }
  out.parameters.odometry = q;
  if (sensor_free) out.parameters.sensor = sensor;
  return out;
}

}  // namespace locbench::calibration
