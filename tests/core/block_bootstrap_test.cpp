#include "core/block_bootstrap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"

namespace locbench {
namespace {

std::vector<double> times(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * dt;
  return t;
}

TEST(BlockBootstrap, RmseOfBlocksEqualsTheSeriesRmse) {
  const std::vector<double> t = times(4, 1.0), e{1.0, -1.0, 3.0, 3.0};
  const ErrorBlocks b = error_blocks(t, e, 0.0, 2.0, 2);
  EXPECT_DOUBLE_EQ(b.squares[0], 2.0);
  EXPECT_DOUBLE_EQ(b.squares[1], 18.0);
  EXPECT_DOUBLE_EQ(b.rmse(), std::sqrt(20.0 / 4.0));
}

TEST(BlockBootstrap, IntervalCoversTheTrueRmseOfCorrelatedErrorsInMostSeeds) {
  // AR(1) errors (ρ = 0.95 per step) of unit stationary variance: the true RMSE is 1.
  int covered = 0;
  const int seeds = 40;
  for (int s = 0; s < seeds; ++s) {
    Rng rng(100 + static_cast<std::uint64_t>(s));
    std::vector<double> e(4000);
    double a = rng.normal();
    for (double& v : e) {
      a = 0.95 * a + std::sqrt(1.0 - 0.95 * 0.95) * rng.normal();
      v = a;
    }
    const ErrorBlocks b = error_blocks(times(e.size(), 1.0), e, 0.0, 100.0, 40);
    const BootstrapInterval ci = block_bootstrap_rmse(b, 400, 7);
    EXPECT_LE(ci.low, b.rmse());
    EXPECT_GE(ci.high, b.rmse());
    covered += ci.low <= 1.0 && 1.0 <= ci.high ? 1 : 0;
  }
  EXPECT_GE(covered, 33);  // 95% nominal; ≥ 33 of 40 has probability > 0.99 at 90% coverage
}

TEST(BlockBootstrap, PairedDifferenceOfIdenticalSeriesIsZero) {
  const std::vector<double> t = times(100, 0.5), e(100, 0.2);
  const ErrorBlocks b = error_blocks(t, e, 0.0, 5.0, 10);
  const BootstrapInterval d = block_bootstrap_rmse_difference(b, b, 200, 3);
  EXPECT_DOUBLE_EQ(d.low, 0.0);
  EXPECT_DOUBLE_EQ(d.high, 0.0);
}

TEST(BlockBootstrap, RejectsEmptyBlocksAndTooFewResamples) {
  EXPECT_THROW(block_bootstrap_rmse(ErrorBlocks{}, 100, 1), std::invalid_argument);
  const ErrorBlocks b = error_blocks(times(10, 1.0), std::vector<double>(10, 1.0), 0.0, 5.0, 2);
  EXPECT_THROW(block_bootstrap_rmse(b, 5, 1), std::invalid_argument);
}

}  // namespace
}  // namespace locbench
