#include "algorithms/filters/quantization_noise.h"

#include <boost/math/special_functions/lambert_w.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace locbench::filters {
namespace {

constexpr double kSqrtPi = 1.7724538509055160273;   // √π
constexpr double kSqrt2Pi = 2.5066282746310005024;  // √(2π)

void require_positive(double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument(std::string(name) + " must be finite and > 0");
  }
}

// argmin_σ f(σ) over σ ∈ [0.05 C, 2 C] by Brent's method (golden section + parabolic steps)
// to about half the double mantissa, the precision limit of a minimiser. The search runs on
// s = σ/C, so the precision is relative whatever the unit (Boost adds an absolute term to the
// tolerance).
template <class F>
double brent_minimum_sigma(F f, double c) {
  constexpr int kBits = std::numeric_limits<double>::digits / 2 + 1;
  std::uintmax_t max_iter = 500;
  auto g = [&](double s) { return f(s * c); };
  return c * boost::math::tools::brent_find_minima(g, 0.05, 2.0, kBits, max_iter).first;
}

double normal_cdf(double x, double sigma) { return 0.5 * std::erfc(-x / (std::numbers::sqrt2 * sigma)); }

}  // namespace

double triangular_density(double e, double c) {
  require_positive(c, "C");
  const double a = std::abs(e);
  return a <= c ? (c - a) / (c * c) : 0.0;
}

double quantization_variance(double c) {
  require_positive(c, "C");
  return c * c / 6.0;
}

double moment_matched_sigma(double c) { return std::sqrt(quantization_variance(c)); }

double l2_distance(double sigma, double c) {
  require_positive(sigma, "sigma");
  require_positive(c, "C");
  // ∫f₁² = 2/(3C); ∫f₂² = 1/(2√π σ); ∫f₁f₂ = (1/C) erf(C/(√2σ)) − 2σ(1 − e^{−C²/2σ²})/(√(2π)C²).
  const double tail = -std::expm1(-c * c / (2.0 * sigma * sigma));
  const double cross = std::erf(c / (std::numbers::sqrt2 * sigma)) / c - 2.0 * sigma * tail / (kSqrt2Pi * c * c);
  return 2.0 / (3.0 * c) + 1.0 / (2.0 * kSqrtPi * sigma) - 2.0 * cross;
}

double l2_distance_derivative(double sigma, double c) {
  require_positive(sigma, "sigma");
  require_positive(c, "C");
  const double tail = -std::expm1(-c * c / (2.0 * sigma * sigma));
  return -1.0 / (2.0 * kSqrtPi * sigma * sigma) + 4.0 * tail / (kSqrt2Pi * c * c);
}

double l2_optimal_sigma(double c) {
  require_positive(c, "C");
  return brent_minimum_sigma([c](double s) { return l2_distance(s, c); }, c);
}

double l2_optimal_sigma_closed_form(double c) {
  require_positive(c, "C");
  const double k = 2.0 * std::numbers::sqrt2;  // 1/a with a = 1/(2√2)
  const double t = k + boost::math::lambert_w0(-k * std::exp(-k));
  return c / std::sqrt(2.0 * t);
}

double thesis_objective(double sigma, double c) {
  require_positive(sigma, "sigma");
  require_positive(c, "C");
  const double tail = -std::expm1(-c * c / (2.0 * sigma * sigma));
  return 1.0 / (4.0 * kSqrtPi * sigma) - std::sqrt(tail) / c + std::numbers::sqrt2 * sigma / (kSqrtPi * c * c) * tail;
}

double thesis_l2_distance(double sigma, double c) { return 2.0 * (thesis_objective(sigma, c) + 1.0 / (3.0 * c)); }

double thesis_optimal_sigma(double c) {
  require_positive(c, "C");
  return brent_minimum_sigma([c](double s) { return thesis_objective(s, c); }, c);
}

double l1_distance(double sigma, double c) {
  require_positive(sigma, "sigma");
  require_positive(c, "C");
  // h(x) = f₁(x) − f₂(x) on [0, C]; for x > C, h = −f₂. By symmetry G₁ = 2∫₀^∞|h|.
  const double norm = 1.0 / (kSqrt2Pi * sigma);
  auto h = [&](double x) { return (c - x) / (c * c) - norm * std::exp(-x * x / (2.0 * sigma * sigma)); };
  // Antiderivative of h on [0, C].
  auto big_h = [&](double x) { return (c * x - 0.5 * x * x) / (c * c) - normal_cdf(x, sigma); };

  // A line and a Gaussian cross at most three times; a 512-cell grid brackets every crossing.
  constexpr int kCells = 512;
  std::vector<double> knots{0.0};
  double x0 = 0.0, h0 = h(0.0);
  for (int i = 1; i <= kCells; ++i) {
    const double x1 = c * i / kCells;
    const double h1 = h(x1);
    if ((h0 < 0.0 && h1 > 0.0) || (h0 > 0.0 && h1 < 0.0)) {
      std::uintmax_t it = 200;
      const auto r =
          boost::math::tools::toms748_solve(h, x0, x1, h0, h1, boost::math::tools::eps_tolerance<double>(52), it);
      knots.push_back(0.5 * (r.first + r.second));
    }
    x0 = x1;
    h0 = h1;
  }
  knots.push_back(c);
  double half = 0.0;
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    half += std::abs(big_h(knots[i + 1]) - big_h(knots[i]));
  }
  half += 0.5 * std::erfc(c / (std::numbers::sqrt2 * sigma));  // ∫_C^∞ f₂
  return 2.0 * half;
}

double l1_optimal_sigma(double c) {
  require_positive(c, "C");
  return brent_minimum_sigma([c](double s) { return l1_distance(s, c); }, c);
}

QuantizationSigmaComparison compare_quantization_sigma(double c, double published_sigma, double published_l2) {
  QuantizationSigmaComparison r;
  r.c = c;
  r.variance = quantization_variance(c);
  r.moment_matched_sigma = moment_matched_sigma(c);
  r.l2_optimal_sigma = l2_optimal_sigma(c);
  r.l2_at_optimum = l2_distance(r.l2_optimal_sigma, c);
  r.l2_at_moment_matched = l2_distance(r.moment_matched_sigma, c);
  r.thesis_optimal_sigma = thesis_optimal_sigma(c);
  r.thesis_l2_at_published = thesis_l2_distance(published_sigma, c);
  r.l2_at_published = l2_distance(published_sigma, c);
  r.l1_optimal_sigma = l1_optimal_sigma(c);
  r.l1_at_l1_optimum = l1_distance(r.l1_optimal_sigma, c);
  r.published_sigma = published_sigma;
  r.published_l2 = published_l2;
  return r;
}

}  // namespace locbench::filters
