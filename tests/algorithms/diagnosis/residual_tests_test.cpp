// The residual battery and the ML fitter on data whose answer is known.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/diagnosis/ml_fit.h"
#include "algorithms/diagnosis/residual_tests.h"
#include "core/rng.h"

namespace locbench::diagnosis {
namespace {

std::vector<double> normal_sample(std::size_t n, std::uint64_t seed, double sigma = 1.0) {
  Rng rng(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = rng.normal(0.0, sigma);
  return v;
}

TEST(ResidualTests, ABiasOfTwoFifthsOfSigmaIsSignificantIn400Samples) {
  auto r = normal_sample(400, 1);
  EXPECT_GT(bias_test(r, "r").p_value, 1e-3);
  for (auto& x : r) x += 0.4;  // z ≈ 0.4·√400 = 8
  EXPECT_LT(bias_test(r, "r").p_value, 1e-6);
}

TEST(ResidualTests, DependenceOnACovariateIsFoundAndItsAbsenceIsNot) {
  const auto x = normal_sample(500, 2);
  auto r = normal_sample(500, 3);
  EXPECT_GT(dependence_test(r, x, "d", "r", "x").p_value, 1e-3);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] += 0.3 * x[i];
  const auto t = dependence_test(r, x, "d", "r", "x");
  EXPECT_LT(t.p_value, 1e-6);
  EXPECT_NEAR(t.strength, 0.3 / std::sqrt(1.09), 0.08);
}

TEST(ResidualTests, HeavyTailsOfAContaminatedNormalAreFound) {
  auto r = normal_sample(1000, 4);
  EXPECT_GT(heavy_tail_test(r, "r").p_value, 1e-3);
  for (std::size_t i = 0; i < r.size(); i += 20) r[i] *= 6.0;  // 5% at 6σ
  EXPECT_LT(heavy_tail_test(r, "r").p_value, 1e-6);
}

TEST(ResidualTests, VarianceGrowingWithTravelIsHeteroscedastic) {
  Rng rng(5);
  std::vector<double> r, travel;
  for (int i = 0; i < 600; ++i) {
    const double w = rng.uniform(0.0, 1.0);
    travel.push_back(w);
    r.push_back(rng.normal(0.0, 0.2 + w));
  }
  EXPECT_LT(heteroscedasticity_test(r, travel, "r", "travel").p_value, 1e-6);
  const auto flat = normal_sample(600, 6);
  EXPECT_GT(heteroscedasticity_test(flat, travel, "r", "travel").p_value, 1e-3);
}

TEST(ResidualTests, PositiveAutocorrelationIsAFindingNegativeIsNot) {
  const auto e = normal_sample(800, 7);
  std::vector<double> ar(e.size()), ma(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) {
    ar[i] = e[i] + (i ? 0.5 * ar[i - 1] : 0.0);
    ma[i] = e[i] - (i ? e[i - 1] : 0.0);  // endpoint noise: ρ₁ = −0.5
  }
  EXPECT_LT(autocorrelation_test(ar, "r").p_value, 1e-10);
  const auto t = autocorrelation_test(ma, "r");
  EXPECT_NEAR(t.strength, -0.5, 0.06);
  EXPECT_EQ(t.p_value, 1.0);
}

TEST(ResidualTests, ALatticeOf2DegreesIsFoundInQuantizedHeadingsAndNoneInContinuousOnes) {
  Rng rng(8);
  const double step = 2.0 * 3.14159265358979 / 180.0;
  std::vector<double> q, c;
  for (int i = 0; i < 300; ++i) {
    const double h = rng.uniform(-3.0, 3.0);
    c.push_back(h);
    q.push_back(step * std::round(h / step));
  }
  const auto lat = find_lattice(q);
  ASSERT_TRUE(lat.has_value());
  EXPECT_NEAR(lat->step, step, 1e-9);
  EXPECT_FALSE(find_lattice(c).has_value());
}

TEST(ResidualTests, IntegerLatticeNeedsSpreadNotJustACommonValue) {
  std::vector<std::int64_t> constant(200, 250), coarse, fine;
  Rng rng(9);
  for (int i = 0; i < 200; ++i) {
    const auto n = static_cast<std::int64_t>(rng.uniform(200.0, 300.0));
    fine.push_back(n);
    coarse.push_back(8 * (n / 8));
  }
  EXPECT_FALSE(find_integer_lattice(constant).has_value());  // a servo at constant speed
  EXPECT_FALSE(find_integer_lattice(fine).has_value());
  const auto lat = find_integer_lattice(coarse);
  ASSERT_TRUE(lat.has_value());
  EXPECT_EQ(lat->step, 8.0);
}

TEST(MaxLikelihoodFit, RecoversTheMeanAndSigmaOfANormalSampleWithCalibratedIntervals) {
  // 200 repetitions: the 95% interval of the mean must cover the truth about 95% of the time.
  int covered = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const auto x = normal_sample(50, 100 + seed, 2.0);
    const auto nll = [&](const std::vector<double>& p) {
      double s = 0.0;
      for (double v : x) s += 0.5 * (v - p[0]) * (v - p[0]) / (p[1] * p[1]) + std::log(p[1]);
      return s;
    };
    const FitResult f = fit_max_likelihood(nll, {{"mu", 0.5, 0.1, false}, {"sigma", 1.0, 0.0, true}});
    ASSERT_TRUE(f.converged);
    covered += f.ci_low[0] <= 0.0 && 0.0 <= f.ci_high[0];
    EXPECT_NEAR(f.values[1], 2.0, 0.8);
  }
  EXPECT_GE(covered, 180);  // binomial(200, 0.95): 180 is 2.6σ below 190
  EXPECT_LE(covered, 197);
}

// A parameter used as |v| (the landmark channel's σ_r) makes v = 0 a stationary point of the NLL. A
// fit that starts there, where the data want |v| = 1, has a zero gradient and a negative curvature:
// the fit leaves the saddle along it and ends at the minimum with a positive definite Hessian.
TEST(MaxLikelihoodFit, LeavesASaddleWhereTheGradientVanishes) {
  const auto nll = [](const std::vector<double>& p) {
    const double a = std::abs(p[0]);
    return (a * a - 1.0) * (a * a - 1.0) + (p[1] - 2.0) * (p[1] - 2.0);
  };
  const FitResult f = fit_max_likelihood(nll, {{"v", 0.0, 0.01, false}, {"w", 0.0, 1.0, false}});
  EXPECT_NEAR(std::abs(f.values[0]), 1.0, 1e-6);
  EXPECT_NEAR(f.values[1], 2.0, 1e-6);
  EXPECT_NEAR(f.nll, 0.0, 1e-12);
  EXPECT_TRUE(f.hessian_ok);
}

}  // namespace
}  // namespace locbench::diagnosis
