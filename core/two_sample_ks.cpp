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

// sup |F_a − F_b| of two sorted samples.
double ks_distance_sorted(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) return 0.0;
  std::size_t i = 0, j = 0;
  double d = 0.0;
  const double n = static_cast<double>(a.size()), m = static_cast<double>(b.size());
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == x) ++i;  // ties advance both CDFs together
    while (j < b.size() && b[j] == x) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / n - static_cast<double>(j) / m));
  }
  return d;
}

}  // namespace

KsBootstrap ks_block_bootstrap(std::span<const double> sample, const std::vector<std::vector<double>>& runs,
                               std::size_t block, int resamples, Rng& rng) {
  KsBootstrap r;
  const std::vector<double> a = finite_sorted(sample);
  std::vector<double> pool;
  std::vector<std::vector<double>> usable;
  for (const auto& run : runs) {
    std::vector<double> finite;
    for (double x : run)
      if (std::isfinite(x)) finite.push_back(x);
    pool.insert(pool.end(), finite.begin(), finite.end());
    if (!finite.empty()) usable.push_back(std::move(finite));
  }
  std::sort(pool.begin(), pool.end());
  r.n = a.size();
  r.pooled = pool.size();
  if (a.empty() || pool.empty()) return r;
  r.d = ks_distance_sorted(a, pool);
  const std::size_t length = std::max<std::size_t>(block, 1);
  int at_least = 0;
  std::vector<double> draw;
  for (int b = 0; b < resamples; ++b) {
    draw.clear();
    while (draw.size() < a.size()) {
      const auto& run =
          usable[static_cast<std::size_t>(rng.uniform() * static_cast<double>(usable.size())) % usable.size()];
      const std::size_t start = static_cast<std::size_t>(rng.uniform() * static_cast<double>(run.size())) % run.size();
      for (std::size_t k = 0; k < length && draw.size() < a.size(); ++k) draw.push_back(run[(start + k) % run.size()]);
    }
    std::sort(draw.begin(), draw.end());
    if (ks_distance_sorted(draw, pool) >= r.d) ++at_least;
  }
  r.resamples = resamples;
  r.p_value = (1.0 + at_least) / (1.0 + resamples);
  return r;
}

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
  r.d = ks_distance_sorted(a, b);
  const double n = static_cast<double>(a.size()), m = static_cast<double>(b.size());
  const double ne = std::sqrt(n * m / (n + m));
  r.p_value = kolmogorov_upper_tail((ne + 0.12 + 0.11 / ne) * r.d);
  return r;
}

}  // namespace locbench
