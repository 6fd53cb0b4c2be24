#include "baselines/filters/vb_akf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/rng.h"

namespace locbench::baselines::filters {
namespace {

TEST(VbAkf, HandComputedSingleIterationUpdate) {
  // Standing still, P(0) = 0, Q = diag(0, 0, q), α(0) = 1, β(0) = R(0), ρ = 1, N = 1:
  // α = 1.5, R = β(0)/1.5, S = q + R, K_θ = q/S, θ = K_θ z, P_θθ = q − q²/S,
  // β = β(0) + ½(z − θ)² + ½ P_θθ.
  VbAkfOptions o;
  o.process_noise = Vector3(0.0, 0.0, 1e-4);
  o.initial_measurement_variance = 3e-4;
  o.forgetting = 1.0;
  o.iterations = 1;
  VbAkf f(o, 0.2, Pose2());
  const double z = 0.02, q = 1e-4, r = 3e-4 / 1.5, s = q + r, th = q / s * z;
  const double pth = q - q * q / s;
  const VbAkfStep st = f.step({0.0, 0.0}, z);
  EXPECT_DOUBLE_EQ(st.shape, 1.5);
  EXPECT_NEAR(st.filter.innovation_variance, s, 1e-18);
  EXPECT_NEAR(st.filter.mean(2), th, 1e-16);
  EXPECT_NEAR(st.filter.covariance(2, 2), pth, 1e-18);
  EXPECT_NEAR(st.scale, 3e-4 + 0.5 * (z - th) * (z - th) + 0.5 * pth, 1e-18);
  EXPECT_NEAR(st.measurement_variance, st.scale / 1.5, 1e-18);
  // Forgetting: α and β shrink by ρ per sample.
  VbAkfOptions g = o;
  g.forgetting = 0.5;
  VbAkf h(g, 0.2, Pose2());
  EXPECT_DOUBLE_EQ(h.step({0.0, 0.0}, std::nullopt).shape, 0.5);
}

// A robot standing still at a fixed heading, a compass with unknown noise σ: the estimate β/α
// converges to σ².
TEST(VbAkf, ConvergesToTheTrueMeasurementVariance) {
  for (double sigma_deg : {0.5, 1.5, 4.0}) {
    const double sigma = deg(sigma_deg);
    VbAkfOptions o;
    o.process_noise = Vector3(1e-12, 1e-12, 1e-12);
    o.initial_measurement_variance = 2.0 * deg(1.0) * deg(1.0);  // the published guess
    o.initial_covariance = Vector3(1e-6, 1e-6, deg(5.0) * deg(5.0));
    o.forgetting = 1.0;
    VbAkf f(o, 0.2, Pose2(0.0, 0.0, 0.3));
    Rng rng(11);
    for (int k = 0; k < 4000; ++k) f.step({0.0, 0.0}, 0.3 + sigma * rng.normal());
    EXPECT_NEAR(f.measurement_variance() / (sigma * sigma), 1.0, 0.06) << sigma_deg;
    EXPECT_NEAR(f.mean()(2), 0.3, 3.0 * sigma / std::sqrt(4000.0)) << sigma_deg;
  }
}

TEST(VbAkf, ForgettingTracksAStepInTheNoise) {
  VbAkfOptions o;
  o.process_noise = Vector3(1e-12, 1e-12, 1e-12);
  o.initial_covariance = Vector3(1e-6, 1e-6, 1e-4);
  o.forgetting = 0.98;  // memory ≈ 50 readings
  VbAkf f(o, 0.2, Pose2());
  Rng rng(3);
  for (int k = 0; k < 1000; ++k) f.step({0.0, 0.0}, deg(1.0) * rng.normal());
  EXPECT_NEAR(f.measurement_variance() / (deg(1.0) * deg(1.0)), 1.0, 0.35);
  for (int k = 0; k < 1000; ++k) f.step({0.0, 0.0}, deg(3.0) * rng.normal());
  EXPECT_NEAR(f.measurement_variance() / (deg(3.0) * deg(3.0)), 1.0, 0.35);
}

TEST(VbAkf, OptionsJson) {
  VbAkfOptions o;
  o.iterations = 5;
  o.forgetting = 1.0;
  const nlohmann::json j = o;
  const auto back = j.get<VbAkfOptions>();
  EXPECT_EQ(back.iterations, 5);
  EXPECT_EQ(back.forgetting, 1.0);
  EXPECT_EQ(nlohmann::json(back), j);
  EXPECT_THROW((nlohmann::json{{"iterations", 0}}.get<VbAkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"iterations", 2.5}}.get<VbAkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"rho", 0.9}}.get<VbAkfOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"forgetting", 0.0}}.get<VbAkfOptions>()), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::filters
