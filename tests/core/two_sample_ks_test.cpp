#include "core/two_sample_ks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"

namespace locbench {
namespace {

TEST(TwoSampleKs, DistanceIsTheLargestGapBetweenTheEmpiricalCdfs) {
  // F_a − F_b at 1…5: 0.2, 0.4, 0.6 − 1/6, 0.8 − 2/6, 1 − 3/6 = 0.5 (the largest).
  const std::vector<double> a{1, 2, 3, 4, 5}, b{3, 4, 5, 6, 7, 8};
  const KsResult r = ks_two_sample(a, b);
  EXPECT_DOUBLE_EQ(r.d, 0.5);
  EXPECT_EQ(r.n, 5u);
  EXPECT_EQ(r.m, 6u);
  // n_e = √(30/11) = 1.6514; λ = (1.6514 + 0.12 + 0.11/1.6514)·0.5 = 0.9190; Q(λ) = 0.3670.
  EXPECT_NEAR(r.p_value, 0.3670, 1e-4);
}

TEST(TwoSampleKs, KolmogorovTailMatchesItsTabulatedCriticalValues) {
  EXPECT_NEAR(kolmogorov_upper_tail(1.36), 0.0495, 1e-4);  // the 5% critical value
  EXPECT_NEAR(kolmogorov_upper_tail(1.63), 0.0098, 1e-4);  // the 1% critical value
  EXPECT_DOUBLE_EQ(kolmogorov_upper_tail(0.0), 1.0);
}

TEST(TwoSampleKs, SameSampleIsDistanceZeroAndDisjointSamplesDistanceOne) {
  const std::vector<double> a{0.3, -1.0, 2.0, 2.0, 5.0};
  const KsResult same = ks_two_sample(a, a);
  EXPECT_DOUBLE_EQ(same.d, 0.0);
  EXPECT_DOUBLE_EQ(same.p_value, 1.0);
  const std::vector<double> low(50, -1.0), high(50, 1.0);
  const KsResult apart = ks_two_sample(low, high);
  EXPECT_DOUBLE_EQ(apart.d, 1.0);
  EXPECT_LT(apart.p_value, 1e-10);
}

TEST(TwoSampleKs, SamplesOfOneDistributionAreRarelyRejectedAndShiftedOnesAre) {
  Rng rng(3);
  int rejected_same = 0, rejected_shifted = 0;
  for (int k = 0; k < 100; ++k) {
    std::vector<double> a, b, c;
    for (int i = 0; i < 200; ++i) {
      a.push_back(rng.normal());
      b.push_back(rng.normal());
      c.push_back(rng.normal(0.5, 1.0));
    }
    rejected_same += ks_two_sample(a, b).p_value < 0.05 ? 1 : 0;
    rejected_shifted += ks_two_sample(a, c).p_value < 0.05 ? 1 : 0;
  }
  EXPECT_LE(rejected_same, 12);     // ≈ 5 expected at the 5% level
  EXPECT_GE(rejected_shifted, 90);  // a half-σ shift with 200 per sample: power ≈ 0.99
}

TEST(TwoSampleKs, NonFiniteValuesAreLeftOutAndEmptySamplesGiveNoEvidence) {
  const std::vector<double> a{1.0, NAN, 2.0, INFINITY}, empty;
  EXPECT_EQ(ks_two_sample(a, a).n, 2u);
  const KsResult r = ks_two_sample(a, empty);
  EXPECT_DOUBLE_EQ(r.d, 0.0);
  EXPECT_DOUBLE_EQ(r.p_value, 1.0);
}

// Residuals correlated in time (AR(1), a = 0.9: about 19 values per independent one) from the
// model itself: the asymptotic p-value, which assumes independence, rejects most of them; the
// block bootstrap keeps near its level, and still rejects a shift of half a σ.
TEST(KsBlockBootstrap, CorrelatedSamplesOfTheModelAreRarelyRejectedAndShiftedOnesAre) {
  Rng rng(4);
  const auto ar = [&](std::size_t n, double shift) {
    std::vector<double> v;
    double x = rng.normal();
    for (std::size_t i = 0; i < n; ++i) {
      x = 0.9 * x + std::sqrt(1.0 - 0.81) * rng.normal();
      v.push_back(x + shift);
    }
    return v;
  };
  int naive = 0, bootstrap = 0, shifted = 0;
  const int trials = 40;
  for (int k = 0; k < trials; ++k) {
    std::vector<std::vector<double>> runs;
    for (int j = 0; j < 20; ++j) runs.push_back(ar(400, 0.0));
    const std::vector<double> same = ar(400, 0.0), moved = ar(400, 1.5);  // 1.5 ≈ 0.5 σ of the block means' spread
    std::vector<double> pool;
    for (const auto& r : runs) pool.insert(pool.end(), r.begin(), r.end());
    naive += ks_two_sample(same, pool).p_value < 0.05 ? 1 : 0;
    bootstrap += ks_block_bootstrap(same, runs, 40, 200, rng).p_value < 0.05 ? 1 : 0;
    shifted += ks_block_bootstrap(moved, runs, 40, 200, rng).p_value < 0.05 ? 1 : 0;
  }
  EXPECT_GE(naive, trials / 2) << "independence assumed: most correlated samples rejected";
  EXPECT_LE(bootstrap, 6) << "≈ 2 expected at the 5% level";
  EXPECT_GE(shifted, trials - 4);
}

TEST(KsBlockBootstrap, AnEmptySampleOrPoolGivesNoEvidence) {
  Rng rng(1);
  const std::vector<double> a{1.0, 2.0}, empty;
  EXPECT_DOUBLE_EQ(ks_block_bootstrap(empty, {a}, 10, 100, rng).p_value, 1.0);
  EXPECT_DOUBLE_EQ(ks_block_bootstrap(a, {}, 10, 100, rng).p_value, 1.0);
}

}  // namespace
}  // namespace locbench
