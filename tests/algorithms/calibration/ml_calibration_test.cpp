// The ML calibration on synthetic samples drawn from its own model: exact recovery without
// noise for every input kind, the noise estimate, fixed parameters, outliers, bad input.
#include "algorithms/calibration/ml_calibration.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "algorithms/calibration/closed_form_calibration.h"
#include "algorithms/calibration/held_out_evaluation.h"
#include "core/errors.h"
#include "core/rng.h"

namespace locbench::calibration {
namespace {

// `n` samples of 1–3 increments mixing straight runs, arcs and turns on the spot, with
// references predicted from `truth` and then disturbed by white noise of σ = (σ_xy, σ_xy, σ_θ).
CalibrationData synthetic(OdometryInputKind kind, const ModelParameters& truth, int n, double sigma_xy,
                          double sigma_theta, std::uint64_t seed, bool sensor = false) {
  CalibrationData d;
  d.kind = kind;
  d.sensor_reference = sensor;
  switch (kind) {
    case OdometryInputKind::kWheelTicks:
      d.meters_per_tick_left = d.meters_per_tick_right = 1e-4;
      d.nominal = Eigen::Vector3d(1.0, 1.0, 0.33);
      break;
    case OdometryInputKind::kWheelAngles: d.nominal = Eigen::Vector3d(0.021, 0.021, 0.09); break;
    default: d.nominal = Eigen::Vector3d(1.0, 1.0, 0.0);
  }
  Rng rng(seed);
  for (int i = 0; i < n; ++i) {
    CalibrationSample s;
    const int parts = 1 + static_cast<int>(rng.uniform(0.0, 3.0));
    for (int k = 0; k < parts; ++k) {
      const double forward = rng.uniform(-0.1, 0.4);  // [m]
      const double turn = rng.uniform(-0.6, 0.6);     // [rad]
      const double dt = rng.uniform(0.2, 1.0);
      switch (kind) {
        case OdometryInputKind::kWheelTicks:
          s.increments.push_back({(forward - 0.165 * turn) / 1e-4, (forward + 0.165 * turn) / 1e-4, dt});
          break;
        case OdometryInputKind::kWheelAngles:
          s.increments.push_back({(forward - 0.045 * turn) / 0.021, (forward + 0.045 * turn) / 0.021, dt});
          break;
        default: s.increments.push_back({forward, turn, dt});
      }
    }
    s.reference = predict_reference(d, s, truth) *
                  Pose2(rng.normal(0.0, sigma_xy), rng.normal(0.0, sigma_xy), rng.normal(0.0, sigma_theta));
    d.samples.push_back(std::move(s));
  }
  return d;
}

ModelParameters params(double a, double b, double c, Pose2 sensor = {}) {
  ModelParameters p;
  p.odometry = Eigen::Vector3d(a, b, c);
  p.sensor = sensor;
  return p;
}

MlCalibrationOptions per_component() {
  MlCalibrationOptions o;
  o.noise.kind = NoiseModelKind::kPerComponent;
  return o;
}

void expect_recovers(const MlCalibrationResult& r, const ModelParameters& truth, double tol) {
  const Eigen::Matrix<double, 6, 1> t = truth.vector();
  const Eigen::Matrix<double, 6, 1> e = r.estimate.vector();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(e(i), t(i), tol) << "parameter " << i;
}

TEST(MlCalibration, NoiseFreeTicksGiveTheTrueScalesAndWheelbase) {
  const ModelParameters truth = params(0.995, 1.004, 0.335);
  const auto r = calibrate_ml(synthetic(OdometryInputKind::kWheelTicks, truth, 60, 0, 0, 1), per_component());
  expect_recovers(r, truth, 1e-9);
  ASSERT_EQ(r.parameters.size(), 3u);
  EXPECT_EQ(r.parameters[0].name, "left_scale");
  EXPECT_EQ(r.parameters[2].nominal, 0.33);
  EXPECT_TRUE(r.converged);
}

TEST(MlCalibration, NoiseFreeWheelAnglesWithASensorGiveRadiiAxleAndMount) {
  const ModelParameters truth = params(0.0207, 0.0209, 0.088, Pose2(-0.006, 0.002, -1.55));
  const auto r =
      calibrate_ml(synthetic(OdometryInputKind::kWheelAngles, truth, 80, 0, 0, 2, /*sensor=*/true), per_component());
  expect_recovers(r, truth, 1e-9);
  ASSERT_EQ(r.parameters.size(), 6u);
  EXPECT_EQ(r.parameters[5].name, "sensor_theta");
  // The closed form is exact on noise-free single-arc samples too (Censi et al.).
  EXPECT_NEAR(r.parameter("b").closed_form, 0.088, 1e-9);
  EXPECT_NEAR(r.parameter("sensor_theta").closed_form, -1.55, 1e-9);
}

TEST(MlCalibration, NoiseFreeBodyAndVelocityIncrementsGiveScalesAndTheThirdTermWhenAsked) {
  const ModelParameters body = params(1.02, 0.97, 0.004);
  MlCalibrationOptions o = per_component();
  o.estimate_rotation_per_distance = true;
  expect_recovers(calibrate_ml(synthetic(OdometryInputKind::kBodyIncrements, body, 60, 0, 0, 3), o), body, 1e-9);
  const ModelParameters vel = params(0.96, 1.05, -0.003);
  o.estimate_rotation_rate_bias = true;
  const auto r = calibrate_ml(synthetic(OdometryInputKind::kVelocityIntegrals, vel, 60, 0, 0, 4), o);
  expect_recovers(r, vel, 1e-9);
  EXPECT_EQ(r.parameters[2].name, "rv_bias");
}

TEST(MlCalibration, WithoutTheOptionTheThirdBodyTermStaysAtItsNominalZero) {
  const auto r = calibrate_ml(synthetic(OdometryInputKind::kBodyIncrements, params(1.02, 0.97, 0.0), 40, 0, 0, 5),
                              per_component());
  EXPECT_EQ(r.parameters.size(), 2u);
  EXPECT_EQ(r.estimate.odometry(2), 0.0);
  EXPECT_THROW(r.parameter("rotation_per_distance"), std::out_of_range);
}

TEST(MlCalibration, PerComponentNoiseIsEstimatedFromTheResiduals) {
  // 2 mm and 5 mrad of reference noise on 400 samples: σ estimates within 10 %.
  const ModelParameters truth = params(0.995, 1.004, 0.335);
  const auto r = calibrate_ml(synthetic(OdometryInputKind::kWheelTicks, truth, 400, 2e-3, 5e-3, 6), per_component());
  EXPECT_NEAR(r.noise(0), 2e-3, 2e-4);
  EXPECT_NEAR(r.noise(1), 2e-3, 2e-4);
  EXPECT_NEAR(r.noise(2), 5e-3, 5e-4);
  EXPECT_NEAR(r.chi2_per_dof, 1.0, 0.05);
  for (const auto& p : r.parameters) {
    EXPECT_LE(std::abs(p.value - truth.odometry(&p - &r.parameters[0])), 4.0 * p.standard_error) << p.name;
  }
  // The covariance is symmetric positive definite and its diagonal gives the standard errors.
  const Eigen::LLT<Eigen::MatrixXd> llt(r.covariance);
  EXPECT_EQ(llt.info(), Eigen::Success);
  EXPECT_NEAR(std::sqrt(r.covariance(2, 2)), r.parameters[2].standard_error, 1e-15);
}

TEST(MlCalibration, FixedParametersKeepTheirNominalValues) {
  MlCalibrationOptions o = per_component();
  o.fixed = {"wheelbase"};
  const auto r =
      calibrate_ml(synthetic(OdometryInputKind::kWheelTicks, params(0.995, 1.004, 0.335), 60, 1e-3, 1e-3, 7), o);
  EXPECT_EQ(r.parameters.size(), 2u);
  EXPECT_EQ(r.estimate.odometry(2), 0.33);
}

TEST(MlCalibration, CensiOutlierRejectionDropsGrossOutliers) {
  // 3 % of the references are off by 5 cm: four rounds of 1 % remove them all (and a few more).
  const ModelParameters truth = params(0.995, 1.004, 0.335);
  CalibrationData d = synthetic(OdometryInputKind::kWheelTicks, truth, 300, 1e-3, 1e-3, 8);
  for (std::size_t i = 0; i < d.samples.size(); i += 33) {
    d.samples[i].reference = d.samples[i].reference * Pose2(0.05, -0.05, 0.2);
  }
  MlCalibrationOptions o = per_component();
  const auto plain = calibrate_ml(d, o);
  o.outliers = {4, 0.01};
  const auto robust = calibrate_ml(d, o);
  for (std::size_t i = 0; i < d.samples.size(); i += 33) EXPECT_FALSE(robust.used[i]) << i;
  EXPECT_GE(robust.samples_rejected, 10u);
  EXPECT_EQ(robust.samples_used + robust.samples_rejected, 300u);
  EXPECT_LT(robust.residual_rms_translation, 0.5 * plain.residual_rms_translation);
  expect_recovers(robust, truth, 1e-3);
}

// Options a caller got wrong are std::invalid_argument; data that cannot be calibrated (none,
// not finite, fewer measurements than parameters) is an InputError naming the data (exit 2).
TEST(MlCalibration, RejectsUnusableInput) {
  CalibrationData empty;
  EXPECT_THROW(calibrate_ml(empty), InputError);
  CalibrationData d = synthetic(OdometryInputKind::kWheelTicks, params(1, 1, 0.33), 10, 1e-3, 1e-3, 9);
  MlCalibrationOptions o;
  o.fixed = {"no_such_parameter"};
  EXPECT_THROW(calibrate_ml(d, o), std::invalid_argument);
  o = {};
  o.outliers = {1, 0.9};
  EXPECT_THROW(calibrate_ml(d, o), std::invalid_argument);
  d.samples[3].increments[0].first = std::nan("");
  EXPECT_THROW(calibrate_ml(d), InputError);
  CalibrationData one = subset(d, 0, 1);
  EXPECT_THROW(calibrate_ml(one), InputError);  // 3 measurements, 3 parameters
}

TEST(HeldOutEvaluation, CalibratedOdometryBeatsTheNominalOnTheHeldOutHalf) {
  // Rotation 5 % short and translation 3 % long: after calibration the held-out relation errors
  // shrink to the reference noise.
  const ModelParameters truth = params(1.03, 1.05, 0.0);
  const CalibrationData d = synthetic(OdometryInputKind::kBodyIncrements, truth, 200, 1e-3, 1e-3, 10);
  const HeldOutEvaluation h = evaluate_held_out(d, per_component());
  EXPECT_EQ(h.training_samples, 100u);
  EXPECT_EQ(h.evaluation_samples, 100u);
  EXPECT_LT(h.calibrated_translation.rmse, 0.5 * h.nominal_translation.rmse);
  EXPECT_LT(h.calibrated_rotation.rmse, 0.5 * h.nominal_rotation.rmse);
  EXPECT_GT(h.translation_rmse_reduction, 0.5);
  // With the true parameters and no noise the relation errors vanish.
  const CalibrationData exact = synthetic(OdometryInputKind::kBodyIncrements, truth, 5, 0, 0, 11);
  const PoseErrors e = relative_motion_errors(exact, truth);
  ASSERT_EQ(e.translation.size(), 5u);
  for (double v : e.translation) EXPECT_NEAR(v, 0.0, 1e-12);
  EXPECT_THROW(evaluate_held_out(d, {}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::calibration
