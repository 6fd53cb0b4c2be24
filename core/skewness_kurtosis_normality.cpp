#include "core/skewness_kurtosis_normality.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/statistics.h"

namespace locbench {
namespace {

NormalityTestResult weighted_test(std::span<const double> x, std::span<const double> w, double alpha) {
  if (!(alpha > 0.0 && alpha < 1.0)) {
    throw std::invalid_argument("skewness_kurtosis_test: alpha must be in (0, 1)");
  }
  NormalityTestResult r;
  r.alpha = alpha;
  double n = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(w[i] >= 0.0) || !std::isfinite(x[i])) {
      throw std::invalid_argument("skewness_kurtosis_test: counts must be >= 0, values finite");
    }
    n += w[i];
    sum += w[i] * x[i];
  }
  if (!(n > 3.0)) throw std::invalid_argument("skewness_kurtosis_test: need n > 3");
  r.n = n;
  r.mean = sum / n;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = x[i] - r.mean;
    r.b2 += w[i] * d * d;
    r.b3 += w[i] * d * d * d;
    r.b4 += w[i] * d * d * d * d;
  }
  r.b2 /= n;
  r.b3 /= n;
  r.b4 /= n;
  if (!(r.b2 > 0.0)) throw std::invalid_argument("skewness_kurtosis_test: constant sample");
  r.stddev = std::sqrt(r.b2);
  r.g1 = r.b3 / std::pow(r.b2, 1.5);                                // (3.5)
  r.g2 = r.b4 / (r.b2 * r.b2);                                      // (3.6)
  r.sigma1 = std::sqrt(6.0 * (n - 2.0) / ((n + 1.0) * (n + 3.0)));  // (3.7)
  r.mu2 = 3.0 - 6.0 / (n + 1.0);                                    // (3.8)
  r.sigma2 = std::sqrt(24.0 * n * (n - 2.0) * (n - 3.0) / ((n + 1.0) * (n + 1.0) * (n + 3.0) * (n + 5.0)));
  r.u1 = r.g1 / r.sigma1;
  r.u2 = (r.g2 - r.mu2) / r.sigma2;
  r.p1 = 2.0 * normal_upper_tail(std::abs(r.u1));
  r.p2 = 2.0 * normal_upper_tail(std::abs(r.u2));
  r.critical = normal_quantile(1.0 - alpha / 4.0);  // z_{α/4} (3.9–3.10)
  r.reject_skewness = std::abs(r.u1) >= r.critical;
  r.reject_kurtosis = std::abs(r.u2) >= r.critical;
  r.normal = !r.reject_skewness && !r.reject_kurtosis;
  return r;
}

}  // namespace

NormalityTestResult skewness_kurtosis_test(std::span<const double> samples, double alpha) {
  const std::vector<double> ones(samples.size(), 1.0);
  return weighted_test(samples, ones, alpha);
}

NormalityTestResult skewness_kurtosis_test_binned(std::span<const double> midpoints, std::span<const double> counts,
                                                  double alpha) {
  if (midpoints.size() != counts.size()) {
    throw std::invalid_argument("skewness_kurtosis_test_binned: midpoints and counts differ in size");
  }
  return weighted_test(midpoints, counts, alpha);
}

}  // namespace locbench
