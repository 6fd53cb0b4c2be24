#include "core/statistics.h"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace locbench {
namespace {
void require_nonempty(std::span<const double> v, const char* what) {
  if (v.empty()) throw std::invalid_argument(std::string(what) + ": empty sample");
}
}  // namespace

double mean(std::span<const double> v) {
  require_nonempty(v, "mean");
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double central_moment(std::span<const double> v, int k) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += std::pow(x - m, k);
  return s / static_cast<double>(v.size());
}

double sample_variance(std::span<const double> v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return s / static_cast<double>(v.size() - 1);
}

double sample_stddev(std::span<const double> v) { return std::sqrt(sample_variance(v)); }

double quantile(std::span<const double> v, double q) {
  require_nonempty(v, "quantile");
  if (!(q >= 0.0 && q <= 1.0)) throw std::invalid_argument("quantile: q outside [0, 1]");
  std::vector<double> s(v.begin(), v.end());
  std::sort(s.begin(), s.end());
  const double h = q * static_cast<double>(s.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, s.size() - 1);
  if (s[hi] == s[lo]) return s[lo];  // also two infinities, whose difference is NaN
  return s[lo] + (h - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

double rms(std::span<const double> v) {
  require_nonempty(v, "rms");
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

double pearson_correlation(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) throw std::invalid_argument("pearson_correlation: samples of unequal length");
  if (a.empty()) return 0.0;
  const double ma = mean(a), mb = mean(b);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

namespace {
std::vector<double> mean_ranks(std::span<const double> v) {
  std::vector<std::size_t> order(v.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return v[i] < v[j]; });
  std::vector<double> rank(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = 0.5 * static_cast<double>(i + j) + 1.0;
    i = j + 1;
  }
  return rank;
}
}  // namespace

double spearman_correlation(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size()) throw std::invalid_argument("spearman_correlation: samples of unequal length");
  const std::vector<double> ra = mean_ranks(a), rb = mean_ranks(b);
  return pearson_correlation(ra, rb);
}

double student_t_critical(double confidence, double dof) {
  boost::math::students_t dist(dof);
  return boost::math::quantile(dist, 0.5 + 0.5 * confidence);
}

double student_t_quantile(double p, double dof) {
  if (!(dof > 0.0)) return normal_quantile(p);
  return boost::math::quantile(boost::math::students_t(dof), p);
}

double student_t_two_sided_tail(double x, double dof) {
  const double a = std::abs(x);
  if (!(dof > 0.0)) return 2.0 * normal_upper_tail(a);
  return 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(dof), a));
}

double normal_quantile(double p) { return boost::math::quantile(boost::math::normal_distribution<double>(), p); }

double normal_upper_tail(double z) {
  return boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), z));
}

double skewness_z(double g1, double n) {
  if (!(n >= 8.0)) throw std::invalid_argument("skewness_z: needs n >= 8");
  const double u1 = g1 * std::sqrt((n + 1.0) * (n + 3.0) / (6.0 * (n - 2.0)));
  const double beta2 =
      3.0 * (n * n + 27.0 * n - 70.0) * (n + 1.0) * (n + 3.0) / ((n - 2.0) * (n + 5.0) * (n + 7.0) * (n + 9.0));
  const double w2 = -1.0 + std::sqrt(2.0 * (beta2 - 1.0));
  const double delta = 1.0 / std::sqrt(0.5 * std::log(w2));
  const double alpha = std::sqrt(2.0 / (w2 - 1.0));
  return delta * std::asinh(u1 / alpha);
}

double kurtosis_z(double b2, double n) {
  if (!(n >= 20.0)) throw std::invalid_argument("kurtosis_z: needs n >= 20");
  const double mean_b2 = 3.0 * (n - 1.0) / (n + 1.0);
  const double var_b2 = 24.0 * n * (n - 2.0) * (n - 3.0) / ((n + 1.0) * (n + 1.0) * (n + 3.0) * (n + 5.0));
  const double x = (b2 - mean_b2) / std::sqrt(var_b2);
  // √β1 of b2's distribution, then Anscombe & Glynn's A.
  const double sqrt_beta1 = 6.0 * (n * n - 5.0 * n + 2.0) / ((n + 7.0) * (n + 9.0)) *
                            std::sqrt(6.0 * (n + 3.0) * (n + 5.0) / (n * (n - 2.0) * (n - 3.0)));
  const double a = 6.0 + 8.0 / sqrt_beta1 * (2.0 / sqrt_beta1 + std::sqrt(1.0 + 4.0 / (sqrt_beta1 * sqrt_beta1)));
  const double denom = 1.0 + x * std::sqrt(2.0 / (a - 4.0));
  // denom ≤ 0 is a b2 far below its mean (platykurtic beyond the transform's range).
  if (!(denom > 0.0)) return -std::numeric_limits<double>::infinity();
  const double term2 = std::cbrt((1.0 - 2.0 / a) / denom);
  return (1.0 - 2.0 / (9.0 * a) - term2) / std::sqrt(2.0 / (9.0 * a));
}

Summary summarize(std::span<const double> v) {
  require_nonempty(v, "summarize");
  Summary s;
  s.n = v.size();
  s.mean = mean(v);
  s.stddev = sample_stddev(v);
  s.median = quantile(v, 0.5);
  const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  s.min = *mn;
  s.max = *mx;
  if (s.n >= 2) {
    const double half =
        student_t_critical(0.95, static_cast<double>(s.n - 1)) * s.stddev / std::sqrt(static_cast<double>(s.n));
    s.ci95_low = s.mean - half;
    s.ci95_high = s.mean + half;
  } else {
    s.ci95_low = s.ci95_high = s.mean;
  }
  return s;
}

}  // namespace locbench

namespace locbench {
namespace {

// Number of ways n1 values of `a` and n2 of `b` can be ordered with exactly u (a > b) pairs:
// f(n1, n2, u) = f(n1 − 1, n2, u − n2) + f(n1, n2 − 1, u) (the largest value is an a or a b).
double u_count(int n1, int n2, int u, std::vector<std::vector<std::vector<double>>>& memo) {
  if (u < 0) return 0.0;
  if (n1 == 0 || n2 == 0) return u == 0 ? 1.0 : 0.0;
  double& m = memo[n1][n2][u];
  if (m >= 0.0) return m;
  m = u_count(n1 - 1, n2, u - n2, memo) + u_count(n1, n2 - 1, u, memo);
  return m;
}

}  // namespace

MannWhitneyResult mann_whitney_u(std::span<const double> a, std::span<const double> b) {
  require_nonempty(a, "mann_whitney_u");
  require_nonempty(b, "mann_whitney_u");
  const int n1 = static_cast<int>(a.size()), n2 = static_cast<int>(b.size());
  MannWhitneyResult r;
  bool ties = false;
  for (double x : a) {
    for (double y : b) {
      if (x > y)
        r.u += 1.0;
      else if (x == y) {
        r.u += 0.5;
        ties = true;
      }
    }
  }
  std::vector<double> all(a.begin(), a.end());
  all.insert(all.end(), b.begin(), b.end());
  std::sort(all.begin(), all.end());
  for (std::size_t i = 1; i < all.size(); ++i) ties = ties || all[i] == all[i - 1];

  const double n1n2 = static_cast<double>(n1) * n2;
  if (!ties && n1 <= 10 && n2 <= 10) {
    std::vector<std::vector<std::vector<double>>> memo(
        n1 + 1, std::vector<std::vector<double>>(n2 + 1, std::vector<double>(n1 * n2 + 1, -1.0)));
    double total = 0.0, at_least = 0.0, at_most = 0.0;
    const int u = static_cast<int>(r.u);
    for (int k = 0; k <= n1 * n2; ++k) {
      const double c = u_count(n1, n2, k, memo);
      total += c;
      if (k >= u) at_least += c;
      if (k <= u) at_most += c;
    }
    r.p_greater = at_least / total;
    r.p_less = at_most / total;
    r.exact = true;
  } else {
    // Tie-corrected variance: n1 n2/12 · ((n + 1) − Σ(t³ − t)/(n(n − 1))).
    const double n = n1 + n2;
    double tie_term = 0.0;
    for (std::size_t i = 0; i < all.size();) {
      std::size_t j = i;
      while (j < all.size() && all[j] == all[i]) ++j;
      const double t = static_cast<double>(j - i);
      tie_term += t * t * t - t;
      i = j;
    }
    const double var = n1n2 / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
    const double mu = n1n2 / 2.0;
    if (var <= 0.0) {
      r.p_greater = r.p_less = 1.0;
    } else {
      const double sd = std::sqrt(var);
      r.p_greater = normal_upper_tail((r.u - mu - 0.5) / sd);
      r.p_less = normal_upper_tail((mu - r.u - 0.5) / sd);
    }
  }
  r.p_two_sided = std::min(1.0, 2.0 * std::min(r.p_greater, r.p_less));
  return r;
}

}  // namespace locbench
