#pragma once
// The skewness–kurtosis normality test of §3.2.1 (eq. 3.3–3.10). With B_k the k-th central
// sample moments (1/n denominator):
//   G1 = B3 / B2^{3/2},  G2 = B4 / B2²                                        (3.5–3.6)
// and under H0 (normal population), for large n,
//   G1 ~ N(0, σ1²),  σ1² = 6(n−2) / ((n+1)(n+3))                              (3.7)
//   G2 ~ N(μ2, σ2²), μ2 = 3 − 6/(n+1), σ2² = 24n(n−2)(n−3) / ((n+1)²(n+3)(n+5)) (3.8)
// U1 = G1/σ1, U2 = (G2 − μ2)/σ2. The thesis splits α equally between the two statistics
// (eq. 3.9–3.10: P{|U_i| ≥ k_i} = α/2), so k1 = k2 = z_{α/4} and H0 is rejected when
// |u1| ≥ z_{α/4} or |u2| ≥ z_{α/4} — a Bonferroni-style combination whose overall level is at
// most α (for α = 0.1: z_{0.025} = 1.96). Implemented as published; the per-statistic two-sided
// p-values 2(1 − Φ(|u_i|)) are given too, H0 is rejected iff min(p1, p2) ≤ α/2.
#include <cstddef>
#include <span>

namespace locbench {

struct NormalityTestResult {
  double n = 0.0;                                // sample size (sum of the counts for a histogram)
  double mean = 0.0;                             // x̄
  double stddev = 0.0;                           // √B2 (the thesis's σ = √(E[x²] − μ²), §3.2.3)
  double b2 = 0.0, b3 = 0.0, b4 = 0.0;           // central moments (eq. 3.5–3.6)
  double g1 = 0.0;                               // sample skewness (3.5)
  double g2 = 0.0;                               // sample kurtosis (3.6), 3 for a normal population
  double sigma1 = 0.0, mu2 = 0.0, sigma2 = 0.0;  // (3.7–3.8)
  double u1 = 0.0;                               // G1/σ1
  double u2 = 0.0;                               // (G2 − μ2)/σ2
  double p1 = 1.0;                               // two-sided p-value of u1: 2(1 − Φ(|u1|))
  double p2 = 1.0;                               // two-sided p-value of u2
  double alpha = 0.1;
  double critical = 0.0;         // z_{α/4}
  bool reject_skewness = false;  // |u1| ≥ z_{α/4}
  bool reject_kurtosis = false;  // |u2| ≥ z_{α/4}
  bool normal = true;            // H0 accepted (neither rejects)
};

// Raw samples (any unit; the statistics are scale-free except mean, stddev, B_k). Throws
// std::invalid_argument when n < 4 (σ2 needs n > 3), α ∉ (0, 1) or the sample is constant.
NormalityTestResult skewness_kurtosis_test(std::span<const double> samples, double alpha = 0.1);

// A binned sample, as Table 3.1: each value is taken at its bin mid-point, weighted by its
// count (non-negative; n = Σ counts). Same errors, plus mismatched lengths.
NormalityTestResult skewness_kurtosis_test_binned(std::span<const double> midpoints, std::span<const double> counts,
                                                  double alpha = 0.1);

}  // namespace locbench
