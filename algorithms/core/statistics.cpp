#include "algorithms/core/statistics.h"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
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
  return s[lo] + (h - static_cast<double>(lo)) * (s[hi] - s[lo]);
}

double rms(std::span<const double> v) {
  require_nonempty(v, "rms");
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

double student_t_critical(double confidence, double dof) {
  boost::math::students_t dist(dof);
  return boost::math::quantile(dist, 0.5 + 0.5 * confidence);
}

double normal_quantile(double p) {
  return boost::math::quantile(boost::math::normal_distribution<double>(), p);
}

double normal_upper_tail(double z) {
  return boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), z));
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
    const double half = student_t_critical(0.95, static_cast<double>(s.n - 1)) * s.stddev /
                        std::sqrt(static_cast<double>(s.n));
    s.ci95_low = s.mean - half;
    s.ci95_high = s.mean + half;
  } else {
    s.ci95_low = s.ci95_high = s.mean;
  }
  return s;
}

}  // namespace locbench
