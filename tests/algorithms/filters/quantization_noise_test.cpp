#include "algorithms/filters/quantization_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/rng.h"

namespace locbench::filters {
namespace {

// Composite Simpson on [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

double normal_pdf(double x, double sigma) {
  return std::exp(-x * x / (2.0 * sigma * sigma)) / (std::sqrt(2.0 * kPi) * sigma);
}

// Integrates piecewise so the kinks of f₁ at −C, 0, C fall on interval ends.
double integrate_with_kinks(const std::function<double(double)>& f, double c, double outer) {
  return simpson(f, -outer, -c, 20000) + simpson(f, -c, 0.0, 20000) + simpson(f, 0.0, c, 20000) +
         simpson(f, c, outer, 20000);
}

TEST(QuantizationNoise, TriangularDensityHasUnitMassZeroMeanAndVarianceCSquaredOverSix) {
  for (double c : {12.64, 12.70, 0.0152}) {
    auto f = [c](double e) { return triangular_density(e, c); };
    EXPECT_NEAR(simpson(f, -c, 0.0, 2000) + simpson(f, 0.0, c, 2000), 1.0, 1e-12);
    auto m1 = [&](double e) { return e * f(e); };
    EXPECT_NEAR(simpson(m1, -c, 0.0, 2000) + simpson(m1, 0.0, c, 2000), 0.0, 1e-12 * c);
    auto m2 = [&](double e) { return e * e * f(e); };
    const double var = simpson(m2, -c, 0.0, 2000) + simpson(m2, 0.0, c, 2000);
    EXPECT_NEAR(var, quantization_variance(c), 1e-10 * c * c);  // eq. 4.21
    EXPECT_DOUBLE_EQ(quantization_variance(c), c * c / 6.0);
  }
  // The thesis's numbers (§4.3): C²/6 = 26.63 mm² for the Trilobot, 0.00004 mm² for the Pioneer.
  EXPECT_NEAR(quantization_variance(12.64), 26.63, 0.005);
  EXPECT_NEAR(quantization_variance(0.0152), 0.00004, 0.000005);
  EXPECT_DOUBLE_EQ(triangular_density(13.0, 12.64), 0.0);
  EXPECT_DOUBLE_EQ(triangular_density(0.0, 12.64), 1.0 / 12.64);
}

TEST(QuantizationNoise, DifferenceOfTwoUniformRemaindersHasTheTriangularVariance) {
  // e = e_k − e_{k+1}, both uniform on [0, C] (eq. 4.13–4.17).
  Rng rng(17);
  const double c = 12.64;
  double s2 = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double e = rng.uniform(0.0, c) - rng.uniform(0.0, c);
    s2 += e * e;
  }
  EXPECT_NEAR(s2 / n, c * c / 6.0, 0.01 * c * c / 6.0);
}

TEST(QuantizationNoise, L2DistanceClosedFormMatchesNumericalIntegration) {
  for (double c : {12.64, 12.70, 1.0}) {
    for (double sigma : {0.2 * c, 0.4 * c, 0.5 * c, 1.3 * c}) {
      auto sq = [&](double x) {
        const double d = triangular_density(x, c) - normal_pdf(x, sigma);
        return d * d;
      };
      const double numeric = integrate_with_kinks(sq, c, c + 12.0 * sigma);
      EXPECT_NEAR(l2_distance(sigma, c), numeric, 1e-10 / c) << "C " << c << " sigma " << sigma;
    }
  }
}

TEST(QuantizationNoise, L2DerivativeMatchesFiniteDifferences) {
  const double c = 12.64;
  for (double sigma : {3.0, 5.0, 5.5, 8.0}) {
    const double h = 1e-5;
    const double fd = (l2_distance(sigma + h, c) - l2_distance(sigma - h, c)) / (2.0 * h);
    EXPECT_NEAR(l2_distance_derivative(sigma, c), fd, 1e-9);
  }
}

TEST(QuantizationNoise, L2OptimalSigmaIsAStationaryMinimumAndMatchesTheLambertWClosedForm) {
  for (double c : {12.64, 12.70, 0.0152, 1.0}) {
    const double s = l2_optimal_sigma(c);
    // Stationary: |dG₂/dσ| tiny against the size of its terms, 1/(2√π σ²).
    EXPECT_LT(std::abs(l2_distance_derivative(s, c)) * 2.0 * std::sqrt(kPi) * s * s, 1e-7);
    // A minimum: beats its neighbours.
    for (double rel : {1e-3, 1e-2, 0.1}) {
      EXPECT_LT(l2_distance(s, c), l2_distance(s * (1.0 + rel), c));
      EXPECT_LT(l2_distance(s, c), l2_distance(s * (1.0 - rel), c));
    }
    EXPECT_NEAR(s, l2_optimal_sigma_closed_form(c), 1e-7 * c);
    EXPECT_NEAR(s / c, 0.4365889, 2e-7);
  }
}

TEST(QuantizationNoise, TrilobotSigmasBesideThePublishedFiveMillimetres) {
  // C = 12.64 mm (left wheel): exact L2 optimum 5.518 mm; moment-matched C/√6 = 5.160 mm;
  // published 5.00 mm, 0.52 mm (9.4%) below the exact optimum.
  EXPECT_NEAR(l2_optimal_sigma(12.64), 5.5185, 5e-4);
  EXPECT_NEAR(moment_matched_sigma(12.64), 5.1603, 5e-4);
  EXPECT_NEAR(l2_optimal_sigma(12.64) - 5.00, 0.5185, 5e-4);
  // C = 12.70 mm (right wheel): 5.545 and 5.185 mm; published 5.00 mm.
  EXPECT_NEAR(l2_optimal_sigma(12.70), 5.5447, 5e-4);
  EXPECT_NEAR(moment_matched_sigma(12.70), 5.1848, 5e-4);
  // The exact minimum G₂ is 2.31e-4 /mm, not the published 0.0021; at σ = 5.00 it is 6.4e-4.
  EXPECT_NEAR(l2_distance(l2_optimal_sigma(12.64), 12.64), 2.3105e-4, 1e-8);
  EXPECT_NEAR(l2_distance(5.00, 12.64), 6.4347e-4, 1e-8);
  // The moment-matched σ is a worse L2 fit than the optimum, better than the published 5.00.
  EXPECT_GT(l2_distance(moment_matched_sigma(12.64), 12.64), l2_distance(5.5185, 12.64));
  EXPECT_LT(l2_distance(moment_matched_sigma(12.64), 12.64), l2_distance(5.00, 12.64));
}

TEST(QuantizationNoise, ThesisObjectiveReproducesThePublishedSigmaAndG2) {
  // Eq. 4.35 (with the quarter-disc evaluation of eq. 4.32) is minimised at 5.02 / 5.04 mm,
  // i.e. 5.0 on a 0.1 mm grid — the published "5.00".
  EXPECT_NEAR(thesis_optimal_sigma(12.64), 5.0195, 5e-4);
  EXPECT_NEAR(thesis_optimal_sigma(12.70), 5.0433, 5e-4);
  EXPECT_NEAR(std::round(thesis_optimal_sigma(12.64) * 10.0) / 10.0, 5.0, 1e-12);
  EXPECT_NEAR(std::round(thesis_optimal_sigma(12.70) * 10.0) / 10.0, 5.0, 1e-12);
  // The published G₂ is 2(g(σ) + 1/(3C)) at σ = 5.00: 0.002102 → "0.0021" (C = 12.64) and
  // 0.002095 → "0.0020" (C = 12.70, truncated rather than rounded).
  EXPECT_NEAR(thesis_l2_distance(5.00, 12.64), 0.0021020, 5e-7);
  EXPECT_NEAR(thesis_l2_distance(5.00, 12.70), 0.0020955, 5e-7);
  EXPECT_NEAR(std::trunc(thesis_l2_distance(5.00, 12.64) * 1e4) / 1e4, 0.0021, 1e-12);
  EXPECT_NEAR(std::trunc(thesis_l2_distance(5.00, 12.70) * 1e4) / 1e4, 0.0020, 1e-12);
  // The quarter-disc step replaces erf(z) by √(1 − e^{−z²}), which is smaller: the thesis's
  // g overstates G₂.
  for (double z : {0.5, 1.0, 1.79, 3.0}) {
    EXPECT_LT(std::sqrt(-std::expm1(-z * z)), std::erf(z));
  }
  EXPECT_GT(thesis_l2_distance(5.00, 12.64), l2_distance(5.00, 12.64));
}

TEST(QuantizationNoise, L1DistanceMatchesNumericalIntegrationAndHasItsOwnOptimum) {
  const double c = 12.64;
  for (double sigma : {3.0, 5.0, 5.6, 9.0}) {
    auto ad = [&](double x) { return std::abs(triangular_density(x, c) - normal_pdf(x, sigma)); };
    // |·| has kinks at the crossings: many intervals make Simpson accurate enough.
    const double numeric = simpson(ad, -c - 12 * sigma, c + 12 * sigma, 2000000);
    EXPECT_NEAR(l1_distance(sigma, c), numeric, 1e-7) << sigma;
  }
  // Eq. 4.27 asks for the L1 optimum; eq. 4.28's L2 optimum is not the same σ.
  const double s1 = l1_optimal_sigma(c);
  EXPECT_NEAR(s1, 5.5937, 5e-4);
  EXPECT_GT(std::abs(s1 - l2_optimal_sigma(c)), 0.05);
  EXPECT_LT(l1_distance(s1, c), l1_distance(l2_optimal_sigma(c), c));
  EXPECT_NEAR(l1_distance(s1, c), 0.0770, 1e-4);
}

TEST(QuantizationNoise, ComparisonCollectsEveryCandidate) {
  const QuantizationSigmaComparison r = compare_quantization_sigma(12.64, 5.00, 0.0021);
  EXPECT_DOUBLE_EQ(r.c, 12.64);
  EXPECT_DOUBLE_EQ(r.l2_optimal_sigma, l2_optimal_sigma(12.64));
  EXPECT_DOUBLE_EQ(r.moment_matched_sigma, moment_matched_sigma(12.64));
  EXPECT_DOUBLE_EQ(r.thesis_optimal_sigma, thesis_optimal_sigma(12.64));
  EXPECT_DOUBLE_EQ(r.published_sigma, 5.00);
  EXPECT_DOUBLE_EQ(r.published_l2, 0.0021);
  EXPECT_LT(r.l2_at_optimum, r.l2_at_moment_matched);
  EXPECT_LT(r.l2_at_moment_matched, r.l2_at_published);
}

TEST(QuantizationNoise, RejectsNonPositiveArguments) {
  EXPECT_THROW(quantization_variance(0.0), std::invalid_argument);
  EXPECT_THROW(l2_distance(-1.0, 12.64), std::invalid_argument);
  EXPECT_THROW(l2_optimal_sigma(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::filters
