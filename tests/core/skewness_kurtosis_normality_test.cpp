// The skewness–kurtosis test (eq. 3.3–3.10) against the thesis's Table 3.1.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/rng.h"
#include "core/skewness_kurtosis_normality.h"

namespace locbench {
namespace {

const std::vector<double> kMid = {-4.5, -3.5, -2.5, -1.5, -0.5, 0.5, 1.5, 2.5, 3.5, 4.5};
const std::vector<double> kCounts = {3, 15, 5, 177, 20, 419, 11, 139, 7, 13};

TEST(NormalityTest, Table31ReproducesThePublishedDigits) {
  const NormalityTestResult r = skewness_kurtosis_test_binned(kMid, kCounts, 0.1);
  EXPECT_EQ(r.n, 809.0);
  // Every printed digit of B2, B3, B4, g1, g2, σ1, μ2, σ2, μ and σ.
  EXPECT_NEAR(r.b2, 2.36482, 0.5e-5);
  EXPECT_NEAR(r.b3, -0.04542, 0.5e-5);
  EXPECT_NEAR(r.b4, 18.41878, 0.5e-5);
  EXPECT_NEAR(r.g1, -0.01249, 0.5e-5);
  EXPECT_NEAR(r.g2, 3.29355, 0.5e-5);
  EXPECT_NEAR(r.sigma1, 0.08580, 0.5e-5);
  EXPECT_NEAR(r.mu2, 2.99259, 0.5e-5);
  EXPECT_NEAR(r.sigma2, 0.17065, 0.5e-5);
  EXPECT_NEAR(r.mean, 0.37, 0.005);
  EXPECT_NEAR(r.stddev, 1.54, 0.005);
  // |u1|, |u2|: ours from unrounded values; the printed 0.14557 and 1.76361 are the rounded
  // g's divided by the rounded σ's — the discrepancy is exactly that rounding.
  EXPECT_NEAR(std::abs(r.u1), 0.14556, 0.5e-5);
  EXPECT_NEAR(r.u2, 1.76359, 0.5e-5);
  EXPECT_NEAR(0.01249 / 0.08580, 0.14557, 0.5e-5);
  EXPECT_NEAR((3.29355 - 2.99259) / 0.17065, 1.76361, 0.5e-5);
  // α = 0.1 → z_{α/4} = z_{0.025} = 1.96; both below: normality accepted.
  EXPECT_NEAR(r.critical, 1.959964, 1e-6);
  EXPECT_FALSE(r.reject_skewness);
  EXPECT_FALSE(r.reject_kurtosis);
  EXPECT_TRUE(r.normal);
  EXPECT_NEAR(r.p1, 2.0 * (1.0 - 0.557868), 1e-4);  // Φ(0.14556) = 0.557868
  EXPECT_GT(r.p2, 0.05);                            // = α/2: accepted exactly because p2 > α/2
  EXPECT_LT(r.p2, 0.1);                             // (the usual single-test rule at α = 0.1 would reject on kurtosis)
}

TEST(NormalityTest, BinnedEqualsRawSamples) {
  std::vector<double> raw;
  for (std::size_t i = 0; i < kMid.size(); ++i) {
    for (int c = 0; c < static_cast<int>(kCounts[i]); ++c) raw.push_back(kMid[i]);
  }
  const auto a = skewness_kurtosis_test(raw, 0.1);
  const auto b = skewness_kurtosis_test_binned(kMid, kCounts, 0.1);
  EXPECT_NEAR(a.g1, b.g1, 1e-12);
  EXPECT_NEAR(a.g2, b.g2, 1e-12);
  EXPECT_NEAR(a.u2, b.u2, 1e-10);
}

TEST(NormalityTest, LevelOnNormalSamplesAndPowerOnUniform) {
  // Under H0 the split rule rejects at most α (Bonferroni): 400 normal samples of n = 809.
  Rng rng(5);
  int rejected = 0;
  for (int rep = 0; rep < 400; ++rep) {
    std::vector<double> x(809);
    for (double& v : x) v = rng.normal(1.0, 2.0);
    rejected += skewness_kurtosis_test(x, 0.1).normal ? 0 : 1;
  }
  EXPECT_LE(rejected, 0.13 * 400);  // α = 0.1 plus sampling slack
  EXPECT_GE(rejected, 0.03 * 400);
  std::vector<double> uniform;
  for (int i = 0; i < 4000; ++i) uniform.push_back(rng.uniform(-1.0, 1.0));
  const auto u = skewness_kurtosis_test(uniform, 0.1);
  EXPECT_NEAR(u.g2, 1.8, 0.1);  // kurtosis of a uniform
  EXPECT_TRUE(u.reject_kurtosis);
  EXPECT_FALSE(u.normal);
}

TEST(NormalityTest, RejectsBadInput) {
  const std::vector<double> three = {1.0, 2.0, 3.0}, constant = {1.0, 1.0, 1.0, 1.0, 1.0};
  EXPECT_THROW(skewness_kurtosis_test(three), std::invalid_argument);
  EXPECT_THROW(skewness_kurtosis_test(constant), std::invalid_argument);
  EXPECT_THROW(skewness_kurtosis_test(kMid, 1.5), std::invalid_argument);
  const std::vector<double> short_counts = {1.0, 2.0};
  EXPECT_THROW(skewness_kurtosis_test_binned(kMid, short_counts), std::invalid_argument);
}

}  // namespace
}  // namespace locbench
