#include "core/block_bootstrap.h"

#include <cmath>
#include <stdexcept>

#include "core/rng.h"
#include "core/statistics.h"

namespace locbench {
namespace {

double rmse_of(double squares, double counts) { return counts > 0.0 ? std::sqrt(squares / counts) : 0.0; }

// The percentile interval of stat(draw) over resamples, draw being the block indices drawn.
template <typename Stat>
BootstrapInterval percentile_interval(std::size_t blocks, int resamples, std::uint64_t seed, double confidence,
                                      Stat stat) {
  if (blocks == 0) throw std::invalid_argument("block bootstrap: no blocks");
  if (resamples < 10) throw std::invalid_argument("block bootstrap: at least 10 resamples");
  Rng rng(seed);
  std::vector<std::size_t> draw(blocks);
  std::vector<double> stats;
  stats.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    for (auto& k : draw)
      k = std::min(static_cast<std::size_t>(rng.uniform() * static_cast<double>(blocks)), blocks - 1);
    stats.push_back(stat(draw));
  }
  const double tail = 0.5 * (1.0 - confidence);
  return {quantile(stats, tail), quantile(stats, 1.0 - tail)};
}

}  // namespace

double ErrorBlocks::rmse() const {
  double s = 0.0, n = 0.0;
  for (std::size_t k = 0; k < squares.size(); ++k) {
    s += squares[k];
    n += counts[k];
  }
  return rmse_of(s, n);
}

ErrorBlocks error_blocks(std::span<const double> times, std::span<const double> errors, double t0, double block_s,
                         std::size_t blocks) {
  if (times.size() != errors.size()) throw std::invalid_argument("error_blocks: times and errors differ in size");
  if (!(block_s > 0.0)) throw std::invalid_argument("error_blocks: block_s must be > 0");
  ErrorBlocks b{std::vector<double>(blocks, 0.0), std::vector<double>(blocks, 0.0)};
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double k = std::floor((times[i] - t0) / block_s);
    if (!(k >= 0.0 && k < static_cast<double>(blocks))) continue;
    b.squares[static_cast<std::size_t>(k)] += errors[i] * errors[i];
    b.counts[static_cast<std::size_t>(k)] += 1.0;
  }
  return b;
}

BootstrapInterval block_bootstrap_rmse(const ErrorBlocks& a, int resamples, std::uint64_t seed, double confidence) {
  return percentile_interval(a.squares.size(), resamples, seed, confidence, [&](const std::vector<std::size_t>& draw) {
    double s = 0.0, n = 0.0;
    for (std::size_t k : draw) {
      s += a.squares[k];
      n += a.counts[k];
    }
    return rmse_of(s, n);
  });
}

BootstrapInterval block_bootstrap_rmse_difference(const ErrorBlocks& a, const ErrorBlocks& b, int resamples,
                                                  std::uint64_t seed, double confidence) {
  if (a.squares.size() != b.squares.size()) {
    throw std::invalid_argument("block_bootstrap_rmse_difference: different block counts");
  }
  return percentile_interval(a.squares.size(), resamples, seed, confidence, [&](const std::vector<std::size_t>& draw) {
    double sa = 0.0, na = 0.0, sb = 0.0, nb = 0.0;
    for (std::size_t k : draw) {
      sa += a.squares[k];
      na += a.counts[k];
      sb += b.squares[k];
      nb += b.counts[k];
    }
    return rmse_of(sa, na) - rmse_of(sb, nb);
  });
}

}  // namespace locbench
