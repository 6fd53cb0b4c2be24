#include "baselines/filters/sage_husa_aekf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace locbench::baselines::filters {
namespace {

constexpr double kA = 6.33e-6;               // 6.33 mm² in m²
constexpr double kC = 6.092348395734171e-4;  // 2 deg² in rad²

TEST(SageHusaAekf, DengForgettingWeights) {
  EXPECT_DOUBLE_EQ(deng_forgetting_weight(0.9, 1), 1.0);  // d(0) = 1
  EXPECT_NEAR(deng_forgetting_weight(0.9, 2), 1.0 / 1.9, 1e-15);
  EXPECT_NEAR(deng_forgetting_weight(0.9, 3), 0.1 / (1.0 - 0.729), 1e-15);
  EXPECT_NEAR(deng_forgetting_weight(0.9, 500), 0.1, 1e-15);  // → 1 − b
  // β_i = d(k−1) bⁱ, i = 0..k−1, sum to 1 (eq. 4.8–4.9).
  for (int k : {1, 2, 7, 40}) {
    double sum = 0.0;
    for (int i = 0; i < k; ++i) sum += deng_forgetting_weight(0.9, k) * std::pow(0.9, i);
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
  EXPECT_THROW(deng_forgetting_weight(0.9, 0), UsageError);
}

TEST(SageHusaAekf, PublishedSettings) {
  const SageHusaOptions o;
  EXPECT_TRUE(o.initial_process_noise.isApprox(Vector3(kA, kA, kC), 1e-15));
  EXPECT_NEAR(o.initial_measurement_noise, kC, 1e-18);
  EXPECT_TRUE(o.initial_process_mean.isZero());
  EXPECT_EQ(o.initial_measurement_mean, 0.0);
  EXPECT_EQ(o.forgetting, 0.9);
  EXPECT_TRUE(o.initial_covariance.isZero());
  EXPECT_TRUE(o.positive_definiteness_fix);
}

TEST(SageHusaAekf, HandComputedFirstAndSecondSteps) {
  // From the origin, straight 62.5 mm per sample, compass z₁, z₂; published settings.
  // Step 1 (d = 1): F(X̂(0)) = (0.0625, 0, 0), ∇F P(0) ∇Fᵀ = 0, P(1/0) = Q̂(0) = diag(a, a, c),
  // ε₁ = z₁, S = c + R̂(0) = 2c, K = (0, 0, ½), X̂(1) = (0.0625, 0, z₁/2),
  // P(1) = diag(a, a, c/2), q̂(1) = (0, 0, z₁/2), Q̂(1) = diag(a, a, z₁²/4 + c/2), r̂(1) = z₁,
  // R̂(1) = z₁² − c (< 0 unless |z₁| > 1.41°; Zhang's fix makes it z₁²).
  const double z1 = deg(0.5), z2 = deg(-0.3);
  for (bool fix : {false, true}) {
    SageHusaOptions o;
    o.positive_definiteness_fix = fix;
    SageHusaAekf f(o, 0.2, Pose2());
    const SageHusaStep s1 = f.step({0.0625, 0.0625}, z1);
    EXPECT_DOUBLE_EQ(s1.weight, 1.0);
    EXPECT_NEAR(s1.filter.innovation, z1, 1e-16);
    EXPECT_NEAR(s1.filter.innovation_variance, 2.0 * kC, 1e-18);
    EXPECT_TRUE(s1.filter.mean.isApprox(Vector3(0.0625, 0.0, z1 / 2.0), 1e-15));
    EXPECT_TRUE(s1.filter.covariance.isApprox(Vector3(kA, kA, kC / 2.0).asDiagonal().toDenseMatrix(), 1e-14));
    EXPECT_TRUE(s1.process_mean.isApprox(Vector3(0.0, 0.0, z1 / 2.0), 1e-15));
    EXPECT_TRUE(s1.process_cov.isApprox(Vector3(kA, kA, z1 * z1 / 4.0 + kC / 2.0).asDiagonal().toDenseMatrix(), 1e-14));
    EXPECT_NEAR(s1.measurement_mean, z1, 1e-16);
    EXPECT_NEAR(s1.measurement_variance, fix ? z1 * z1 : z1 * z1 - kC, 1e-18);
    EXPECT_EQ(s1.measurement_fix_applied, fix);
    EXPECT_FALSE(s1.process_fix_applied);
    EXPECT_EQ(s1.measurement_variance_positive, fix);

    // Step 2 (d = 1/1.9): θ̂(2/1) = θ̂(1) + q̂θ(1) = z₁, Ẑ = z₁ + r̂(1) = 2z₁, ε₂ = z₂ − 2z₁;
    // P(2/1)θθ = P(1)θθ + Q̂(1)θθ = c + z₁²/4 (the θ row of ∇F is (0, 0, 1)).
    const SageHusaStep s2 = f.step({0.0625, 0.0625}, z2);
    const double d = 1.0 / 1.9;
    const double r1 = fix ? z1 * z1 : z1 * z1 - kC;
    const double pp = kC + z1 * z1 / 4.0;
    const double eps = z2 - 2.0 * z1;
    EXPECT_NEAR(s2.weight, d, 1e-15);
    EXPECT_NEAR(s2.filter.innovation, eps, 1e-15);
    EXPECT_NEAR(s2.filter.innovation_variance, pp + r1, 1e-15);
    EXPECT_NEAR(s2.measurement_mean, (1.0 - d) * z1 + d * (z2 - z1), 1e-15);
    const double r2 = (1.0 - d) * r1 + d * (eps * eps - pp);
    const double r2_expected = fix && !(r2 > 0.0) ? r2 + d * pp : r2;
    EXPECT_NEAR(s2.measurement_variance, r2_expected, 1e-15);
  }
}

TEST(SageHusaAekf, WithoutACompassReadingTheStatisticsStay) {
  SageHusaAekf f(SageHusaOptions{}, 0.2, Pose2());
  const SageHusaStep s = f.step({0.0625, 0.0625}, std::nullopt);
  EXPECT_FALSE(s.filter.updated);
  EXPECT_EQ(s.weight, 0.0);
  EXPECT_EQ(f.updates(), 0);
  EXPECT_TRUE(s.process_cov.isApprox(Vector3(kA, kA, kC).asDiagonal().toDenseMatrix(), 1e-15));
  EXPECT_TRUE(s.filter.covariance.isApprox(s.process_cov, 1e-15));
}

// A compass far better than the assumed R̂(0) = 2 deg²: it reads ±0.1° around the true heading
// 0 while the robot drives straight. The unfixed estimator drives R̂ negative at once and Q̂
// indefinite a few steps later, then diverges; Zhang's fix keeps both positive definite.
TEST(SageHusaAekf, ZhangFixKeepsTheNoiseEstimatesPositiveDefinite) {
  struct Outcome {
    int q_not_pd = 0, r_not_pd = 0, first_q = -1, first_r = -1;
    double max_heading_error = 0.0;
  };
  auto run = [](bool fix) {
    SageHusaOptions o;
    o.positive_definiteness_fix = fix;
    SageHusaAekf f(o, 0.19793, Pose2());
    Outcome out;
    for (int k = 1; k <= 40; ++k) {
      const SageHusaStep s = f.step({0.0625, 0.0625}, deg(k % 2 ? 0.1 : -0.1));
      if (!is_positive_definite(s.process_cov)) {
        ++out.q_not_pd;
        if (out.first_q < 0) out.first_q = k;
      }
      if (!(s.measurement_variance > 0.0)) {
        ++out.r_not_pd;
        if (out.first_r < 0) out.first_r = k;
      }
      EXPECT_EQ(s.process_cov_positive_definite, is_positive_definite(s.process_cov));
      out.max_heading_error = std::max(out.max_heading_error, std::abs(s.filter.mean(2)));
    }
    return out;
  };
  const Outcome unfixed = run(false);
  EXPECT_EQ(unfixed.first_r, 1);
  EXPECT_GT(unfixed.r_not_pd, 20);
  EXPECT_GT(unfixed.first_q, 1);
  EXPECT_GT(unfixed.q_not_pd, 20);
  EXPECT_GT(unfixed.max_heading_error, deg(30.0));  // diverged

  const Outcome fixed = run(true);
  EXPECT_EQ(fixed.q_not_pd, 0);
  EXPECT_EQ(fixed.r_not_pd, 0);
  EXPECT_LT(fixed.max_heading_error, deg(2.0));
}

TEST(SageHusaAekf, OptionsJson) {
  SageHusaOptions o;
  o.forgetting = 0.95;
  o.positive_definiteness_fix = false;
  const nlohmann::json j = o;
  const auto back = j.get<SageHusaOptions>();
  EXPECT_EQ(back.forgetting, 0.95);
  EXPECT_FALSE(back.positive_definiteness_fix);
  EXPECT_EQ(nlohmann::json(back), j);
  EXPECT_THROW((nlohmann::json{{"forgetting", 1.0}}.get<SageHusaOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"positive_definiteness_fix", 1}}.get<SageHusaOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"lambda", 0.9}}.get<SageHusaOptions>()), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::filters
