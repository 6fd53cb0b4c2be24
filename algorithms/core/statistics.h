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

struct Summary {
  std::size_t n = 0;
  double mean = 0.0;
  double stddev = 0.0;   // sample standard deviation (0 when n < 2)
  double ci95_low = 0.0;  // 95% confidence interval of the mean (Student t, n − 1 dof)
  double ci95_high = 0.0;
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
};
Summary summarize(std::span<const double> v);

// Two-sided Student-t critical value t_{1−α/2, dof} (Boost.Math).
double student_t_critical(double confidence, double dof);
// Standard normal quantile Φ⁻¹(p) and upper-tail probability 1 − Φ(z).
double normal_quantile(double p);
double normal_upper_tail(double z);

}  // namespace locbench
