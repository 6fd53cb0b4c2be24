#include "algorithms/diagnosis/residual_tests.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/chi_square.h"
#include "core/statistics.h"

namespace locbench::diagnosis {

double two_sided_normal_p(double z) { return std::min(1.0, 2.0 * normal_upper_tail(std::abs(z))); }

namespace {

// Test `t` with its strength, its statistic z and z's two-sided normal p-value.
ResidualTest two_sided_z_test(ResidualTest t, double strength, double z) {
  t.strength = strength;
  t.value = z;
  t.p_value = two_sided_normal_p(z);
  return t;
}

}  // namespace

ResidualTest bias_test(std::span<const double> r, const std::string& residual) {
  const double n = static_cast<double>(r.size());
  const double s = sample_stddev(r);
  const double strength = s > 0.0 ? mean(r) / s : 0.0;
  return two_sided_z_test({"bias", residual, "", "z"}, strength, strength * std::sqrt(n));
}

ResidualTest dependence_test(std::span<const double> r, std::span<const double> x, const std::string& name,
                             const std::string& residual, const std::string& variable) {
  const double rho = std::clamp(pearson_correlation(r, x), -0.999999, 0.999999);
  return two_sided_z_test({name, residual, variable, "z"}, rho,
                          std::atanh(rho) * std::sqrt(std::max(0.0, static_cast<double>(r.size()) - 3.0)));
}

// The thesis's moment statistics (eqs. 3.5–3.8), with p-values from their normalising
// transforms (core/statistics.h): read as N(0, 1), u1 and u2 reject normal residuals far more
// often than the stated level at the small per-test levels the diagnosis uses.
ResidualTest skewness_test(std::span<const double> r, const std::string& residual) {
  const double n = static_cast<double>(r.size());
  const double b2 = central_moment(r, 2), b3 = central_moment(r, 3);
  const double g1 = b2 > 0.0 ? b3 / std::pow(b2, 1.5) : 0.0;  // (3.5)
  return two_sided_z_test({"normality_skewness", residual, "", "z_dagostino"}, g1, n >= 8.0 ? skewness_z(g1, n) : 0.0);
}

ResidualTest heavy_tail_test(std::span<const double> r, const std::string& residual) {
  ResidualTest t{"heavy_tails", residual, "", "z_anscombe_glynn"};
  const double n = static_cast<double>(r.size());
  const double b2 = central_moment(r, 2), b4 = central_moment(r, 4);
  const double g2 = b2 > 0.0 ? b4 / (b2 * b2) : 3.0;  // (3.6)
  t.strength = g2 - 3.0;
  t.value = n >= 20.0 ? kurtosis_z(g2, n) : 0.0;
  t.p_value = normal_upper_tail(t.value);  // one-sided: tails heavier than normal
  return t;
}

ResidualTest heteroscedasticity_test(std::span<const double> r, std::span<const double> x, const std::string& residual,
                                     const std::string& variable) {
  std::vector<double> r2(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) r2[i] = r[i] * r[i];
  ResidualTest t = dependence_test(r2, x, "heteroscedasticity", residual, variable);
  t.p_value = normal_upper_tail(t.value);  // one-sided: variance growing with x
  return t;
}

ResidualTest autocorrelation_test(std::span<const double> r, const std::string& residual) {
  ResidualTest t{"autocorrelation", residual, "lag 1", "ljung_box_q"};
  const double n = static_cast<double>(r.size());
  const double m = mean(r);
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    c0 += (r[i] - m) * (r[i] - m);
    if (i > 0) c1 += (r[i] - m) * (r[i - 1] - m);
  }
  const double rho = c0 > 0.0 ? c1 / c0 : 0.0;
  t.strength = rho;
  t.value = n * (n + 2.0) * rho * rho / (n - 1.0);
  // One-sided: a slowly varying unmodelled effect makes neighbours alike (ρ > 0). Noise at the
  // window ends — quantization remainders, reference noise — is shared by adjacent windows with
  // opposite signs and gives ρ ≈ −0.5 under a correct model, so ρ < 0 is not a finding.
  t.p_value = rho > 0.0 ? 0.5 * chi_square_upper_tail(ChiSquareDof(1.0), t.value) : 1.0;
  return t;
}

namespace {

// The resolution values were printed at: 10^−d for the fewest decimals d ≤ 9 that reproduce
// every value; 0 when they need more (full precision).
double print_quantum(const std::vector<double>& v) {
  for (int d = 0; d <= 9; ++d) {
    const double scale = std::pow(10.0, d);
    const bool all = std::all_of(v.begin(), v.end(), [&](double x) {
      const double y = x * scale;
      return std::abs(y - std::round(y)) <= 64.0 * 2.220446049250313e-16 * std::max(1.0, std::abs(y));
    });
    if (all) return 1.0 / scale;
  }
  return 0.0;
}

}  // namespace

std::optional<Lattice> find_lattice(std::span<const double> values) {
  if (values.size() < 20) return std::nullopt;
  std::vector<double> v(values.begin(), values.end());
  std::sort(v.begin(), v.end());
  const double quantum = print_quantum(v);
  std::vector<double> distinct;
  for (double x : v) {
    if (distinct.empty() || x - distinct.back() > std::max(1e-9, 0.5 * quantum)) distinct.push_back(x);
  }
  // Quantized values repeat; continuous ones (almost) never do.
  if (distinct.size() < 2 || static_cast<double>(distinct.size()) > 0.9 * static_cast<double>(v.size())) {
    return std::nullopt;
  }
  const double min_step = std::max(1e-6 * (v.back() - v.front()), 4.0 * quantum);
  std::vector<double> gaps;
  for (std::size_t i = 1; i < distinct.size(); ++i) gaps.push_back(distinct[i] - distinct[i - 1]);
  std::sort(gaps.begin(), gaps.end());
  std::optional<Lattice> best;
  const double n = static_cast<double>(v.size());
  // Candidates: the smallest gaps and their integer fractions (a lattice whose every other
  // value is missing still shows its step as the smallest gap's divisor).
  for (std::size_t g = 0; g < std::min<std::size_t>(gaps.size(), 5); ++g) {
    for (int div = 1; div <= 4; ++div) {
      double s = gaps[g] / div;
      if (!(s > min_step)) continue;
      double o = distinct.front();
      double se = 0.0;
      // Least squares x = o + s·k over all values, k from the current lattice (twice).
      for (int round = 0; round < 2; ++round) {
        double sk = 0.0, sx = 0.0, skk = 0.0, skx = 0.0;
        for (double x : v) {
          const double k = std::round((x - o) / s);
          sk += k, sx += x, skk += k * k, skx += k * x;
        }
        const double det = n * skk - sk * sk;
        if (!(det > 0.0)) break;
        const double s_new = (n * skx - sk * sx) / det;
        if (!(s_new > 0.5 * s && s_new < 1.5 * s)) break;
        o = (sx - s_new * sk) / n;
        s = s_new;
        double ss = 0.0;
        for (double x : v) {
          const double e = x - o - s * std::round((x - o) / s);
          ss += e * e;
        }
        se = std::sqrt(ss / std::max(n - 2.0, 1.0) * n / det);
      }
      const double tol = std::max(1e-3 * s, 0.75 * quantum);
      if (tol > 0.25 * s) continue;
      std::size_t on = 0;
      for (double x : v) {
        if (std::abs(x - o - s * std::round((x - o) / s)) <= tol) ++on;
      }
      const double frac = static_cast<double>(on) / n;
      if (frac >= 0.99 && (!best || s > best->step * (1.0 + 1e-6))) {
        double off = o - s * std::round(o / s);
        if (off >= 0.5 * s) off -= s;
        // An exact lattice has se = 0: the interval is floored at the arithmetic's resolution.
        best = Lattice{s, frac, distinct.size(), v.size(), off, std::max(1.959963984540054 * se, 1e-9 * s), quantum};
      }
    }
  }
  return best;
}

std::optional<Lattice> find_integer_lattice(std::span<const std::int64_t> increments) {
  std::vector<std::int64_t> nz;
  for (auto d : increments) {
    if (d != 0) nz.push_back(d < 0 ? -d : d);
  }
  if (nz.size() < 20) return std::nullopt;
  // A lattice needs spread: increments that take only a few values (a servo at constant speed
  // sampled on a fixed clock) are divisible by anything that divides those values.
  std::vector<std::int64_t> sorted = nz;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t distinct = static_cast<std::size_t>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  if (distinct < 10) return std::nullopt;
  const std::int64_t median = sorted[distinct / 2];
  std::optional<Lattice> best;
  for (std::int64_t g = 2; g <= std::min<std::int64_t>(1000, median / 3); ++g) {
    std::size_t on = 0;
    for (auto d : nz) on += d % g == 0 ? 1 : 0;
    const double frac = static_cast<double>(on) / static_cast<double>(nz.size());
    if (frac >= 0.99) best = Lattice{static_cast<double>(g), frac, distinct, nz.size()};
  }
  return best;
}

}  // namespace locbench::diagnosis
