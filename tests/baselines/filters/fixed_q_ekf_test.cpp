#include "baselines/filters/fixed_q_ekf.h"

#include <gtest/gtest.h>

#include "algorithms/filters/compass_ekf.h"
#include "core/errors.h"
#include "tests/algorithms/filters/corridor_harness.h"

namespace locbench::baselines::filters {
using locbench::filters::CompassEkf, locbench::filters::pair_encoder_compass;
namespace {

constexpr double kTwoDeg2 = 6.092348395734171e-4;  // 2 deg² in rad²

TEST(FixedQEkf, PublishedSettingsConvertedToSi) {
  const FixedQEkfOptions o;
  EXPECT_DOUBLE_EQ(o.process_noise(0), 6.33e-6);  // 6.33 mm² → m²
  EXPECT_DOUBLE_EQ(o.process_noise(1), 6.33e-6);
  EXPECT_NEAR(o.process_noise(2), kTwoDeg2, 1e-18);  // 2 deg² → rad²
  EXPECT_NEAR(o.compass_variance, kTwoDeg2, 1e-18);
  EXPECT_TRUE(o.initial_covariance.isZero());
}

TEST(FixedQEkf, HandComputedStep) {
  // From the origin with P(0) = 0, straight 62.5 mm, compass 0.01 rad: P⁻ = Q, S = 2c,
  // K = (0, 0, ½), θ = 0.005, P = diag(6.33e-6, 6.33e-6, c/2).
  FixedQEkf ekf(FixedQEkfOptions{}, 0.2, Pose2());
  const CompassFilterStep s = ekf.step({0.0625, 0.0625}, 0.01);
  ASSERT_TRUE(s.updated);
  EXPECT_NEAR(s.innovation, 0.01, 1e-16);
  EXPECT_NEAR(s.innovation_variance, 2.0 * kTwoDeg2, 1e-18);
  EXPECT_NEAR(s.mean(0), 0.0625, 1e-16);
  EXPECT_NEAR(s.mean(1), 0.0, 1e-16);
  EXPECT_NEAR(s.mean(2), 0.005, 1e-16);
  EXPECT_NEAR(s.covariance(0, 0), 6.33e-6, 1e-20);
  EXPECT_NEAR(s.covariance(1, 1), 6.33e-6, 1e-20);
  EXPECT_NEAR(s.covariance(2, 2), 0.5 * kTwoDeg2, 1e-18);
  EXPECT_NEAR(s.covariance(1, 2), 0.0, 1e-20);
  // Next step: the heading variance now couples into y through ∇F (eq. 4.2).
  const CompassFilterStep t = ekf.step({0.0625, 0.0625}, std::nullopt);
  EXPECT_FALSE(t.updated);
  EXPECT_NEAR(t.covariance(1, 2), 0.0625 * std::cos(0.005) * 0.5 * kTwoDeg2, 1e-15);
}

TEST(FixedQEkf, AgreesWithTheGenericCompassEkfGivenTheSameQ) {
  // The baseline duplicates the EKF loop; the algorithm's CompassEkf with a fixed-Q plug-in
  // must give the same numbers on a whole simulated run.
  const auto res = sim::simulate(sim::preset("corridor"), 3);
  const NominalModel m = *res.log.nominal_model();
  const auto steps = pair_encoder_compass(res.log.encoders, res.log.compass, m, 0.125);
  const FixedQEkfOptions o;
  FixedQEkf a(o, m.wheelbase, res.wheel_samples[0].pose);
  const Matrix3 q = o.process_noise.asDiagonal();
  CompassEkf b([&](const Vector3&, const WheelDisplacement&, double) { return q; }, o.compass_variance, Matrix3::Zero(),
               m.wheelbase, res.wheel_samples[0].pose);
  for (const auto& s : steps) {
    const CompassFilterStep x = a.step(s.u, s.compass), y = b.step(s.u, s.compass);
    ASSERT_TRUE(x.mean.isApprox(y.mean, 1e-14));
    ASSERT_TRUE(x.covariance.isApprox(y.covariance, 1e-14));
  }
}

TEST(FixedQEkf, OptionsJson) {
  FixedQEkfOptions o;
  o.process_noise = Vector3(1e-6, 2e-6, 3e-6);
  const nlohmann::json j = o;
  EXPECT_EQ(j.get<FixedQEkfOptions>().process_noise, o.process_noise);
  EXPECT_EQ(nlohmann::json(j.get<FixedQEkfOptions>()), j);
  EXPECT_THROW((nlohmann::json{{"Q", {1, 2, 3}}}.get<FixedQEkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"process_noise", {1, -2, 3}}}.get<FixedQEkfOptions>()), UsageError);
  EXPECT_THROW(FixedQEkf(FixedQEkfOptions{}, -0.2, Pose2()), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::filters
