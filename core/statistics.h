#pragma once
// Small statistics helpers: moments, quantiles and confidence intervals.
#include <span>
#include <vector>

namespace locbench {

double mean(std::span<const double> v);
// k-th central sample moment B_k = (1/n) Σ (x_i − x̄)^k (as in eq. 3.3–3.5).
double central_moment(std::span<const double> v, int k);
// Unbiased sample variance (n − 1 denominator) and its square root.
double sample_variance(std::span<const double> v);
double sample_stddev(std::span<const double> v);
// Quantile with linear interpolation between order statistics (type 7, as R and NumPy).
double quantile(std::span<const double> v, double q);
double rms(std::span<const double> v);
// Pearson's correlation of paired samples (0 when either is constant); throws
// std::invalid_argument for unequal lengths.
double pearson_correlation(std::span<const double> a, std::span<const double> b);
// Spearman's rank correlation: Pearson's of the ranks, ties given their mean rank.
double spearman_correlation(std::span<const double> a, std::span<const double> b);

struct Summary {
  std::size_t n = 0;
  double mean = 0.0;
  double stddev = 0.0;    // sample standard deviation (0 when n < 2)
  double ci95_low = 0.0;  // 95% confidence interval of the mean (Student t, n − 1 dof)
  double ci95_high = 0.0;
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
};
Summary summarize(std::span<const double> v);

// Two-sided Student-t critical value t_{1−α/2, dof} (Boost.Math).
double student_t_critical(double confidence, double dof);
// Student-t with `dof` degrees of freedom (dof = 0: the standard normal): the quantile F⁻¹(p)
// and the two-sided tail P(|T| > x) (Boost.Math).
double student_t_quantile(double p, double dof);
double student_t_two_sided_tail(double x, double dof);
// Standard normal quantile Φ⁻¹(p) and upper-tail probability 1 − Φ(z).
double normal_quantile(double p);
double normal_upper_tail(double z);

// Normalising transforms of the moment tests of normality, for n independent samples from a
// normal law. The plain standardisations u1 = g1/σ(g1) and u2 = (b2 − E b2)/σ(b2) (thesis eqs.
// 3.7–3.8) are far from normal in the tails for n in the hundreds — b2 is right-skewed, so
// reading u2 as N(0, 1) rejects a normal sample several times more often than the stated level
// at small α. These return an approximately N(0, 1) z instead:
//   skewness_z   D'Agostino (1970): z = δ·asinh(u1/α)  (n ≥ 8);
//   kurtosis_z   Anscombe & Glynn (1983): z from the cube-root transform of u2  (n ≥ 20).
// g1 = m3/m2^{3/2} (sample skewness), b2 = m4/m2² (Pearson kurtosis, 3 for a normal law).
double skewness_z(double g1, double n);
double kurtosis_z(double b2, double n);

}  // namespace locbench

namespace locbench {

// Mann–Whitney U test of two independent samples. U counts pairs (a_i, b_j) with a_i > b_j
// (ties count ½). p-values are exact when both samples have at most 10 values and no ties
// (all orderings enumerated by recursion), else from the normal approximation with tie
// correction and continuity correction.
struct MannWhitneyResult {
  double u = 0.0;
  double p_greater = 1.0;  // H1: values of `a` tend to be larger than those of `b`
  double p_less = 1.0;     // H1: values of `a` tend to be smaller
  double p_two_sided = 1.0;
  bool exact = false;
};
MannWhitneyResult mann_whitney_u(std::span<const double> a, std::span<const double> b);

}  // namespace locbench
