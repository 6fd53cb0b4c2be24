// The exact Jacobian of the ML calibration's residual (reference_residual_with_jacobian), which
// Ceres uses instead of numeric differences: checked against Richardson-extrapolated central
// differences (error O(h⁴)) at random parameter points, for every input kind, with and without a
// sensor, and as the whitened Jacobian Ceres evaluates over a subset of free parameters.
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "algorithms/calibration/calibration_model.h"
#include "algorithms/calibration/ml_calibration_solver.h"
#include "core/units.h"

namespace locbench::calibration {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Jacobian = Eigen::Matrix<double, 3, Eigen::Dynamic>;

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// Data of `kind` with a nominal parameter set; the model's parameters are drawn around it.
CalibrationData data_of(OdometryInputKind kind, bool sensor) {
  CalibrationData d;
  d.kind = kind;
  d.sensor_reference = sensor;
  d.meters_per_tick_left = 1.0e-3;
  d.meters_per_tick_right = 1.1e-3;
  switch (kind) {
    case OdometryInputKind::kWheelTicks: d.nominal = Eigen::Vector3d(1.0, 1.0, 0.5); break;
    case OdometryInputKind::kWheelAngles: d.nominal = Eigen::Vector3d(0.04, 0.04, 0.3); break;
    case OdometryInputKind::kBodyIncrements:
    case OdometryInputKind::kVelocityIntegrals: d.nominal = Eigen::Vector3d(1.0, 1.0, 0.0); break;
  }
  return d;
}

ModelParameters random_parameters(const CalibrationData& d, std::mt19937& rng) {
  ModelParameters p;
  const bool wheels = d.kind == OdometryInputKind::kWheelTicks || d.kind == OdometryInputKind::kWheelAngles;
  for (int j = 0; j < 2; ++j) p.odometry(j) = d.nominal(j) * uniform(rng, 0.9, 1.1);
  p.odometry(2) = wheels ? d.nominal(2) * uniform(rng, 0.9, 1.1) : uniform(rng, -0.05, 0.05);
  p.sensor = Pose2(uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3), uniform(rng, -3.0, 3.0));
  return p;
}

// 1–8 increments of up to ~0.3 m and ~0.5 rad each; with probability ½ one of them turns by only
// 1e-5 rad under `p` (the series branch of the arc terms).
CalibrationSample random_sample(const CalibrationData& d, const ModelParameters& p, std::mt19937& rng) {
  CalibrationSample s;
  const int n = std::uniform_int_distribution<int>(1, 8)(rng);
  for (int k = 0; k < n; ++k) {
    OdometryIncrement inc;
    switch (d.kind) {
      case OdometryInputKind::kWheelTicks: inc = {uniform(rng, -100.0, 300.0), uniform(rng, -100.0, 300.0), 0.1}; break;
      case OdometryInputKind::kWheelAngles: inc = {uniform(rng, -2.0, 8.0), uniform(rng, -2.0, 8.0), 0.1}; break;
      case OdometryInputKind::kBodyIncrements:
      case OdometryInputKind::kVelocityIntegrals:
        inc = {uniform(rng, -0.1, 0.3), uniform(rng, -0.5, 0.5), uniform(rng, 0.05, 0.2)};
        break;
    }
    s.increments.push_back(inc);
  }
  if (std::bernoulli_distribution(0.5)(rng)) {
    OdometryIncrement& inc = s.increments.back();
    const Eigen::Vector3d& q = p.odometry;
    const double tiny = 1e-5;
    switch (d.kind) {
      case OdometryInputKind::kWheelTicks:  // Δθ = (q₁c_R·n_R − q₀c_L·n_L)/B
        inc.second = (tiny * q(2) + q(0) * d.meters_per_tick_left * inc.first) / (q(1) * d.meters_per_tick_right);
        break;
      case OdometryInputKind::kWheelAngles: inc.second = (tiny * q(2) + q(0) * inc.first) / q(1); break;
      case OdometryInputKind::kBodyIncrements: inc.second = (tiny - q(2) * inc.first) / q(1); break;
      case OdometryInputKind::kVelocityIntegrals: inc.second = (tiny - q(2) * inc.dt) / q(1); break;
    }
  }
  // A reference near the prediction: the angle residual stays far from the ±π wrap.
  const Pose2 e = predict_reference(d, s, p);
  s.reference =
      Pose2(e.x + uniform(rng, -0.05, 0.05), e.y + uniform(rng, -0.05, 0.05), e.theta + uniform(rng, -0.1, 0.1));
  return s;
}

// ∂f/∂v by Richardson extrapolation of central differences, (4·D(h/2) − D(h))/3, with
// h = 1e-4·max(|v_j|, 0.1): truncation O(h⁴) and rounding ~1e-12, far below the 1e-6 tolerance.
template <typename F>
Jacobian numeric_jacobian(const F& f, const Eigen::VectorXd& v) {
  Jacobian J(3, v.size());
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    const double h = 1e-4 * std::max(std::abs(v(j)), 0.1);
    auto central = [&](double step) {
      Eigen::VectorXd a = v, b = v;
      a(j) += step;
      b(j) -= step;
      return Eigen::Vector3d((f(a) - f(b)) / (2.0 * step));
    };
    J.col(j) = (4.0 * central(h / 2.0) - central(h)) / 3.0;
  }
  return J;
}

// Largest difference in each column relative to that column's largest entry (at least 1e-3, for a
// column of zeros).
double worst_column_error(const Jacobian& exact, const Jacobian& numeric) {
  double worst = 0.0;
  for (Eigen::Index j = 0; j < exact.cols(); ++j) {
    const double scale = std::max(numeric.col(j).cwiseAbs().maxCoeff(), 1e-3);
    worst = std::max(worst, (exact.col(j) - numeric.col(j)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

TEST(CalibrationModelJacobian, MatchesHighAccuracyNumericDerivativesForEveryInputKind) {
  std::mt19937 rng(20261125);
  for (OdometryInputKind kind : {OdometryInputKind::kWheelTicks, OdometryInputKind::kWheelAngles,
                                 OdometryInputKind::kBodyIncrements, OdometryInputKind::kVelocityIntegrals}) {
    for (bool sensor : {false, true}) {
      const CalibrationData d = data_of(kind, sensor);
      double worst = 0.0;
      for (int trial = 0; trial < 40; ++trial) {
        const ModelParameters p = random_parameters(d, rng);
        const CalibrationSample s = random_sample(d, p, rng);
        const ResidualWithJacobian rj = reference_residual_with_jacobian(d, s, p);
        // The same residual as the plain function, to the bit.
        const Eigen::Vector3d r = reference_residual(d, s, p);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(rj.residual(c), r(c));
        const Jacobian numeric = numeric_jacobian(
            [&](const Eigen::VectorXd& v) { return reference_residual(d, s, ModelParameters::from_vector(v)); },
            p.vector());
        worst = std::max(worst, worst_column_error(rj.jacobian, numeric));
        if (!sensor) {
          EXPECT_EQ(rj.jacobian.rightCols<3>(), Eigen::Matrix3d::Zero());
        }
      }
      EXPECT_LT(worst, 1e-6) << "kind " << static_cast<int>(kind) << ", sensor " << sensor;
    }
  }
}

TEST(CalibrationModelJacobian, ATurnOnTheSpotMovesAMountedSensorAsDerivedByHand) {
  // Robot turns Δθ = q₁·π/2 on the spot; sensor at ℓ = (1, 0, 0): s_t = R(oθ)ℓ_t − ℓ_t =
  // (cos oθ − 1, sin oθ), so ∂s_x/∂q₁ = −sin(oθ)·π/2 = −π/2, ∂s_y/∂q₁ = 0 at q₁ = 1;
  // ∂s_t/∂ℓ_x = (cos oθ − 1, sin oθ) = (−1, 1); ∂s_t/∂ℓθ = ∂R(−ℓθ)/∂ℓθ·s_t = (s_y, −s_x) = (1, 1).
  CalibrationData d;
  d.kind = OdometryInputKind::kBodyIncrements;
  d.sensor_reference = true;
  CalibrationSample s;
  s.increments.push_back({0.0, kPi / 2.0, 1.0});
  ModelParameters p;
  p.sensor = Pose2(1.0, 0.0, 0.0);
  const Eigen::Matrix<double, 3, 6> J = reference_residual_with_jacobian(d, s, p).jacobian;
  EXPECT_NEAR(J(0, 1), -kPi / 2.0, 1e-12);
  EXPECT_NEAR(J(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(J(2, 1), kPi / 2.0, 1e-12);
  EXPECT_NEAR(J(0, 3), -1.0, 1e-12);
  EXPECT_NEAR(J(1, 3), 1.0, 1e-12);
  EXPECT_NEAR(J(0, 5), 1.0, 1e-12);
  EXPECT_NEAR(J(1, 5), 1.0, 1e-12);
  EXPECT_EQ(J(2, 5), 0.0);
}

TEST(MlCalibrationSolver, CeresEvaluatesTheWhitenedExactJacobianOverTheFreeParameters) {
  // Four free parameters of six (wheel scale, wheelbase, sensor x and θ), 5 samples, each with
  // its own whitening matrix: the Jacobian Ceres assembles is Wᵢ·∂rᵢ/∂x in the free columns and
  // matches numeric differences of the whitened residuals.
  std::mt19937 rng(7);
  const CalibrationData base = data_of(OdometryInputKind::kWheelTicks, true);
  const ModelParameters p = random_parameters(base, rng);
  CalibrationData d = base;
  for (int i = 0; i < 5; ++i) d.samples.push_back(random_sample(d, p, rng));
  ml_solver::Problem pb{d, {0, 1, 2, 3, 4}, {0, 2, 3, 5}, p.vector()};
  ml_solver::Whitening w;
  for (int i = 0; i < 5; ++i) {
    Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c <= r; ++c) {
        L(r, c) = r == c ? uniform(rng, 1.0, 100.0) : uniform(rng, -5.0, 5.0);
      }
    }
    w.push_back(L);
  }
  Eigen::VectorXd x = pb.free_values(pb.base);
  const Eigen::VectorXd x0 = x;
  const auto problem = ml_solver::whitened_problem(pb, w, x);
  const Eigen::MatrixXd J = ml_solver::whitened_jacobian(*problem, 15, 4);
  for (int i = 0; i < 5; ++i) {
    const Eigen::Matrix3d& wi = w[static_cast<std::size_t>(i)];
    const CalibrationSample& si = d.samples[static_cast<std::size_t>(i)];
    const Eigen::Matrix<double, 3, 6> Ji = wi * reference_residual_with_jacobian(d, si, p).jacobian;
    const Jacobian numeric = numeric_jacobian(
        [&](const Eigen::VectorXd& free) {
          return Eigen::Vector3d(wi * pb.residuals(pb.full(free)).segment<3>(3 * i));
        },
        x0);
    for (int j = 0; j < 4; ++j) {
      for (int r = 0; r < 3; ++r) {
        const double expected = Ji(r, pb.free[static_cast<std::size_t>(j)]);
        EXPECT_NEAR(J(3 * i + r, j), expected, 1e-12 * std::max(1.0, std::abs(expected)));
      }
    }
    EXPECT_LT(worst_column_error(J.middleRows(3 * i, 3), numeric), 1e-6) << "sample " << i;
  }
}

}  // namespace
}  // namespace locbench::calibration
