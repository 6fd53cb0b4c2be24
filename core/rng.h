#pragma once
// The only source of randomness: an explicitly seeded generator passed by reference.
// Distributions are implemented here (not std::normal_distribution, whose output differs
// between standard libraries) so a seed gives the same numbers with any compiler.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

#include "core/units.h"

namespace locbench {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // An independent stream for sub-task `index` of a run with this seed (Monte-Carlo run k,
  // sensor j...), so results do not depend on the order or thread tasks run in.
  static Rng stream(std::uint64_t seed, std::uint64_t index) { return Rng(derive_seed(seed, index)); }
  // The seed of sub-task `index` of a run with base seed `seed` (recorded in reports). Kept
  // below 2^53 so every JSON reader, JavaScript included, reads it back exactly.
  static std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t index) {
    return splitmix64(seed ^ splitmix64(index + 0x9E3779B97F4A7C15ULL)) & kMaxJsonSafeSeed;
  }
  static constexpr std::uint64_t kMaxJsonSafeSeed = (std::uint64_t{1} << 53) - 1;

  // Uniform on [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  bool bernoulli(double p) { return uniform() < p; }
  // A uniform index in [0, n) (n > 0).
  std::size_t index(std::size_t n) {
    return std::min(n - 1, static_cast<std::size_t>(uniform() * static_cast<double>(n)));
  }
  // Standard normal by Box–Muller (cached second value).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }
  double normal(double mean, double sigma) { return mean + sigma * normal(); }
  // χ²_k as 2·Gamma(k/2) (Marsaglia–Tsang; k/2 < 1 boosted by U^(2/k)).
  double chi_square(double k) {
    double shape = 0.5 * k, boost = 1.0;
    if (shape < 1.0) {
      double u = uniform();
      while (u <= 0.0) u = uniform();
      boost = std::pow(u, 1.0 / shape);
      shape += 1.0;
    }
    const double d = shape - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    for (;;) {
      double x = normal(), v = 1.0 + c * x;
      if (v <= 0.0) continue;
      v = v * v * v;
      const double u = uniform();
      if (u > 0.0 && std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) {
        return 2.0 * d * v * boost;
      }
    }
  }

  // Student-t with `dof` degrees of freedom (unit scale), as a normal over √(χ²_dof/dof); normal
  // for dof ≤ 0.
  double student_t(double dof) {
    const double z = normal();
    return dof > 0.0 ? z / std::sqrt(chi_square(dof) / dof) : z;
  }

  static std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace locbench
