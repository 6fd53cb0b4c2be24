#include "algorithms/filters/compass_ekf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"

namespace locbench::filters {
namespace {

constexpr double kR = 6.092348395734171e-4;  // 2 deg² in rad²

TEST(CompassEkfModel, PredictionIsTheOdometryStepWithItsJacobian) {
  const MotionPrediction p = predict_motion(Vector3(1.0, 2.0, 0.5), {0.06, 0.065}, 0.2);
  const double mid = 0.5 + 0.0125;
  EXPECT_NEAR(p.mean(0), 1.0 + 0.0625 * std::cos(mid), 1e-15);
  EXPECT_NEAR(p.mean(1), 2.0 + 0.0625 * std::sin(mid), 1e-15);
  EXPECT_NEAR(p.mean(2), 0.525, 1e-15);
  EXPECT_NEAR(p.jacobian(0, 2), -0.0625 * std::sin(mid), 1e-15);
  EXPECT_NEAR(p.jacobian(1, 2), 0.0625 * std::cos(mid), 1e-15);
}

TEST(CompassEkfModel, InnovationIsWrappedAcrossPlusMinusPi) {
  const Vector3 x(0.0, 0.0, deg(179.0));
  const Matrix3 p = Matrix3::Identity() * 1e-4;
  const LinearizedMeasurement m = linearize(CompassHeading{deg(-179.0), 1e-4}, x);
  const MeasurementUpdate c = measurement_innovation(m, p, m.R);
  EXPECT_NEAR(c.innovation(0), deg(2.0), 1e-12);
  EXPECT_NEAR(c.innovation_covariance(0, 0), 2e-4, 1e-18);
  EXPECT_NEAR(c.gain(2), 0.5, 1e-15);
  Vector3 xu = x;
  Matrix3 pu = p;
  apply_measurement_update(xu, pu, c, m);
  EXPECT_NEAR(xu(2), deg(-180.0), 1e-12);  // 179° + 1° wraps to −180°
  EXPECT_NEAR(pu(2, 2), 0.5e-4, 1e-18);
}

TEST(CompassEkf, HandComputedStep) {
  // Start at the origin, P(0) = 0, published adaptive model, U_L = 60 mm, U_R = 65 mm,
  // B = 0.2 m, compass 0.03 rad.
  CompassEkf ekf(CompassEkfOptions{}, 0.2, Pose2());
  const CompassFilterStep s = ekf.step({0.060, 0.065}, 0.03);
  const double mid = 0.0125;
  const double vd = 1.328125e-5, vt = 1.328125e-3;  // eq. 4.36–4.37 (see noise-model test)
  const double qxx = vd * std::cos(mid) * std::cos(mid), qyy = vd * std::sin(mid) * std::sin(mid);
  const double sv = vt + kR;  // S = P⁻_θθ + R with P⁻ = Q(0) since P(0) = 0
  const double eps = 0.03 - 0.025;
  ASSERT_TRUE(s.updated);
  EXPECT_NEAR(s.innovation, eps, 1e-15);
  EXPECT_NEAR(s.innovation_variance, sv, 1e-15);
  EXPECT_NEAR(s.mean(0), 0.0625 * std::cos(mid), 1e-15);
  EXPECT_NEAR(s.mean(1), 0.0625 * std::sin(mid), 1e-15);
  EXPECT_NEAR(s.mean(2), 0.025 + vt / sv * eps, 1e-15);  // K_θ = P⁻_θθ/S, K_x = K_y = 0
  EXPECT_NEAR(s.covariance(0, 0), qxx, 1e-18);
  EXPECT_NEAR(s.covariance(1, 1), qyy, 1e-18);
  EXPECT_NEAR(s.covariance(2, 2), vt * kR / sv, 1e-15);
  EXPECT_NEAR(s.covariance(0, 2), 0.0, 1e-18);
  EXPECT_EQ(ekf.mean(), s.mean);
}

TEST(CompassEkf, WithoutACompassReadingItOnlyPredicts) {
  CompassEkfOptions o;
  o.initial_covariance = Vector3(1e-4, 2e-4, 1e-3);
  CompassEkf ekf(o, 0.2, Pose2(0.0, 0.0, 0.3));
  const CompassFilterStep s = ekf.step({0.05, 0.05}, std::nullopt);
  EXPECT_FALSE(s.updated);
  const MotionPrediction p = predict_motion(Vector3(0.0, 0.0, 0.3), {0.05, 0.05}, 0.2);
  const Matrix3 expected = p.jacobian * o.initial_covariance.asDiagonal() * p.jacobian.transpose() +
                           adaptive_process_noise(o.noise, 0.3, {0.05, 0.05}, 0.2);
  EXPECT_TRUE(s.covariance.isApprox(expected, 1e-14));
  EXPECT_TRUE(s.mean.isApprox(p.mean, 1e-15));
}

TEST(CompassEkf, ProcessNoiseIsPluggableAndScalable) {
  const Matrix3 fixed = Vector3(1e-6, 1e-6, 1e-4).asDiagonal();
  CompassEkf custom([&](const Vector3&, const WheelDisplacement&, double) { return fixed; }, kR, Matrix3::Zero(), 0.2,
                    Pose2());
  const CompassFilterStep a = custom.step({0.0, 0.0}, std::nullopt);
  EXPECT_TRUE(a.covariance.isApprox(fixed, 1e-15));

  CompassEkfOptions o;
  o.process_noise_scale = 0.25;
  CompassEkf scaled(o, 0.2, Pose2());
  const CompassFilterStep b = scaled.step({0.06, 0.065}, std::nullopt);
  EXPECT_TRUE(b.covariance.isApprox(0.25 * adaptive_process_noise(o.noise, 0.0, {0.06, 0.065}, 0.2), 1e-14));
}

TEST(CompassEkf, OptionsJsonRoundTripAndValidation) {
  CompassEkfOptions o;
  o.noise.k_left = 0.002;
  o.compass_variance = 1e-4;
  o.initial_covariance = Vector3(1e-6, 2e-6, 3e-6);
  o.process_noise_scale = 0.5;
  const nlohmann::json j = o;
  const auto back = j.get<CompassEkfOptions>();
  EXPECT_DOUBLE_EQ(back.noise.k_left, 0.002);
  EXPECT_DOUBLE_EQ(back.compass_variance, 1e-4);
  EXPECT_EQ(back.initial_covariance, o.initial_covariance);
  EXPECT_DOUBLE_EQ(back.process_noise_scale, 0.5);
  EXPECT_EQ(nlohmann::json(back), j);
  // Defaults: R = 2 deg² in rad².
  EXPECT_NEAR(CompassEkfOptions{}.compass_variance, kR, 1e-18);
  EXPECT_THROW((nlohmann::json{{"noise", {{"kk", 1}}}}.get<CompassEkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"compass_variance", 0.0}}.get<CompassEkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"initial_covariance", {1, 2}}}.get<CompassEkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"R", 1.0}}.get<CompassEkfOptions>()), UsageError);
  EXPECT_THROW(CompassEkf(CompassEkfOptions{}, 0.0, Pose2()), UsageError);
}

}  // namespace
}  // namespace locbench::filters
