#pragma once
// The battery of residual tests: does a residual have a bias, depend on a covariate, have
// non-normal or heavy tails, sit on a lattice, grow in variance with travel, correlate with its
// neighbour? Each test returns its statistic and a p-value; `passed` means not significant at
// the level the caller gives (the diagnosis divides its false-alarm level over the battery).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace locbench::diagnosis {

struct ResidualTest {
  std::string name;       // e.g. "drift_with_distance"
  std::string residual;   // e.g. "heading" (what was tested)
  std::string variable;   // covariate, "" for none
  std::string statistic;  // e.g. "z", "chi2", "lattice_fraction"
  double value = 0.0;
  double p_value = 1.0;
  double strength = 0.0;  // effect size: correlation, mean/σ, excess kurtosis, …
  bool passed = true;
};

// Mean of r is zero (z = mean/(s/√n)).
ResidualTest bias_test(std::span<const double> r, const std::string& residual);
// Pearson correlation of r with x (z = atanh(ρ)·√(n − 3)).
ResidualTest dependence_test(std::span<const double> r, std::span<const double> x, const std::string& name,
                             const std::string& residual, const std::string& variable);
// Skewness (3.3–3.10, §3.2.1) of standardized residuals, two-sided.
ResidualTest skewness_test(std::span<const double> r, const std::string& residual);
// Kurtosis above normal (heavy tails), one-sided upper.
ResidualTest heavy_tail_test(std::span<const double> r, const std::string& residual);
// Variance growing with x: correlation of r² with x, one-sided (Breusch–Pagan-like).
ResidualTest heteroscedasticity_test(std::span<const double> r, std::span<const double> x, const std::string& residual,
                                     const std::string& variable);
// Positive lag-1 autocorrelation (Ljung–Box with one lag, χ²₁, one-sided).
ResidualTest autocorrelation_test(std::span<const double> r, const std::string& residual);

// A lattice in real values: values = offset + k·step. The largest step such that at least 99%
// of the values lie within the tolerance of the lattice; candidates are the smallest gaps between
// distinct values and their halves, thirds and quarters, each refined by least squares over all
// values (printed values carry round-off: a step read off one gap of "%.6f" values is 1e-6 off,
// which ±90 steps magnify beyond any tolerance). The tolerance is the larger of 1e-3·step and
// the printing's round-off (half the last printed decimal, found from the values). nullopt when
// there is none, when fewer than 20 values, or when the values hardly repeat (more than 90%
// distinct: continuous data).
struct Lattice {
  double step = 0.0;
  double on_lattice_fraction = 0.0;
  std::size_t distinct = 0;
  std::size_t n = 0;
  double offset = 0.0;            // in [−step/2, step/2)
  double step_uncertainty = 0.0;  // 95% half-width of the least-squares step
  double print_quantum = 0.0;     // the printing's resolution found (0: full precision)
};
std::optional<Lattice> find_lattice(std::span<const double> values);
// A common divisor > 1 of integer increments: the largest g ≤ 1000 dividing at least 99% of
// the non-zero ones (and at least 20 of them).
std::optional<Lattice> find_integer_lattice(std::span<const std::int64_t> increments);

// p-value helpers.
double two_sided_normal_p(double z);

}  // namespace locbench::diagnosis
