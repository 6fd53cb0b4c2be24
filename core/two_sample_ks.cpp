#include "core/two_sample_ks.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace locbench {
namespace {

std::vector<double> finite_sorted(std::span<const double> v) {
  std::vector<double> out;
  out.reserve(v.size());
  for (double x : v) {
    if (std::isfinite(x)) out.push_back(x);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

double kolmogorov_upper_tail(double lambda) {
  if (lambda < 1e-3) return 1.0;
  double sum = 0.0, sign = 1.0, previous = 0.0;
  for (int k = 1; k <= 100; ++k) {
    const double term = sign * 2.0 * std::exp(-2.0 * k * k * lambda * lambda);
    sum += term;
    if (std::abs(term) <= 1e-10 * std::abs(previous) || std::abs(term) <= 1e-16 * sum) return std::clamp(sum, 0.0, 1.0);
    sign = -sign;
    previous = term;
  }
  return 1.0;  // the series has not converged: λ is tiny, p → 1
}

KsResult ks_two_sample(std::span<const double> a_in, std::span<const double> b_in) {
  const std::vector<double> a = finite_sorted(a_in), b = finite_sorted(b_in);
  KsResult r;
  r.n = a.size();
  r.m = b.size();
  if (a.empty() || b.empty()) return r;
  std::size_t i = 0, j = 0;
  const double n = static_cast<double>(a.size()), m = static_cast<double>(b.size());
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == x) ++i;  // ties advance both CDFs together
    while (j < b.size() && b[j] == x) ++j;
    r.d = std::max(r.d, std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m));
  }
  const double ne = std::sqrt(n * m / (n + m));
  r.p_value = kolmogorov_upper_tail((ne + 0.12 + 0.11 / ne) * r.d);
  return r;
}

}  // namespace locbench
