#pragma once
// A block bootstrap of an RMSE along a log (errors correlated in time): the errors are grouped
// into consecutive blocks of fixed duration (non-overlapping blocks, Carlstein 1986); a resample
// draws as many blocks with replacement and its RMSE is √(Σ e² / Σ n) over the drawn blocks; the
// interval is the percentile interval over the resamples. Paired: two methods' errors grouped into
// the same blocks get the same draws, for the interval of their difference. Seeded.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace locbench {

struct BootstrapInterval {
  double low = 0.0;
  double high = 0.0;
};

// Σ e² and the count per block [t0 + k·block_s, t0 + (k + 1)·block_s), k = 0 … blocks − 1 (values
// outside are left out).
struct ErrorBlocks {
  std::vector<double> squares;
  std::vector<double> counts;
  double rmse() const;  // over all blocks; 0 when empty
};
// Throws std::invalid_argument for times and errors of different sizes or block_s <= 0.
ErrorBlocks error_blocks(std::span<const double> times, std::span<const double> errors, double t0, double block_s,
                         std::size_t blocks);

// Throws std::invalid_argument for no blocks, resamples < 10 or (difference) different block counts.
BootstrapInterval block_bootstrap_rmse(const ErrorBlocks& a, int resamples, std::uint64_t seed,
                                       double confidence = 0.95);
// RMSE(a) − RMSE(b) with the same blocks drawn for both.
BootstrapInterval block_bootstrap_rmse_difference(const ErrorBlocks& a, const ErrorBlocks& b, int resamples,
                                                  std::uint64_t seed, double confidence = 0.95);

}  // namespace locbench
