#pragma once
// Two-sample Kolmogorov–Smirnov test: D = sup_x |F_a(x) − F_b(x)| of the two empirical CDFs,
// with the asymptotic p-value P(K > (√n_e + 0.12 + 0.11/√n_e)·D), n_e = n·m/(n + m), K the
// Kolmogorov distribution (Stephens' small-sample correction; Numerical Recipes §14.3).
// Distribution-free and O((n + m) log(n + m)); D is the largest vertical gap between the
// CDFs a chart of both samples shows. The p-value assumes independent samples.
#include <cstddef>
#include <span>
#include <vector>

#include "core/rng.h"

namespace locbench {

struct KsResult {
  double d = 0.0;  // in [0, 1]
  double p_value = 1.0;
  std::size_t n = 0, m = 0;
};

// Non-finite values are left out; an empty sample gives D = 0, p = 1.
KsResult ks_two_sample(std::span<const double> a, std::span<const double> b);

// The KS distance of `sample` (in time order) from the pool of `runs` (samples of a model, each
// in time order), with a p-value that keeps the correlation of neighbouring values, which the
// asymptotic p-value of ks_two_sample ignores: a block bootstrap of the runs. Each of `resamples`
// draws is sample.size() values made of blocks of `block` consecutive values of a random run
// from a random start; its D against the same pool is one draw of D under "the sample comes from
// the model"; p = (1 + #{D_b ≥ D})/(1 + resamples). Non-finite values are left out; an empty sample
// or pool gives D = 0, p = 1.
struct KsBootstrap {
  double d = 0.0;
  double p_value = 1.0;
  std::size_t n = 0, pooled = 0;
  int resamples = 0;
};
KsBootstrap ks_block_bootstrap(std::span<const double> sample, const std::vector<std::vector<double>>& runs,
                               std::size_t block, int resamples, Rng& rng);

// Q_KS(λ) = 2 Σ_{k≥1} (−1)^{k−1} exp(−2k²λ²), the Kolmogorov distribution's upper tail.
double kolmogorov_upper_tail(double lambda);

}  // namespace locbench
