// Floor noise δ ~ N(0, k²|U|) per wheel and sample (eq. 4.16).
#include "datasets/sim/floor_noise.h"

#include <gtest/gtest.h>

#include "core/statistics.h"
#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

TEST(FloorNoise, IsZeroWithoutTravelOrWithoutK) {
  FloorNoise n(FloorNoiseConfig{0.0, 0.01}, Rng(1), Rng(2));
  EXPECT_EQ(n.left(0.5), 0.0);
  EXPECT_EQ(n.right(0.0), 0.0);
  EXPECT_NE(n.right(0.5), 0.0);
}

// δ per encoder sample = rim travel − ground travel, for a straight run at `speed`.
std::vector<double> floor_errors(double speed, bool left) {
  Scenario s = testing::quiet_straight(200.0);
  s.drive.speed = speed;
  s.floor = {0.005, 0.01};
  s.encoders.timing.rate = 4.0;
  const auto r = simulate(s, 3);
  const auto& w = r.wheel_samples;
  std::vector<double> d;
  for (std::size_t i = 2; i + 2 < w.size(); ++i) {
    d.push_back(left ? (w[i].rim_left - w[i - 1].rim_left) - (w[i].ground_left - w[i - 1].ground_left)
                     : (w[i].rim_right - w[i - 1].rim_right) - (w[i].ground_right - w[i - 1].ground_right));
  }
  return d;
}

TEST(FloorNoise, VarianceIsKSquaredTimesTravelPerSample) {
  // 0.5 m/s at 4 Hz: |U| = 0.125 m per sample; k_l = 0.005 → σ² = 3.125e-6 m².
  const auto left = floor_errors(0.5, true);
  EXPECT_NEAR(mean(left), 0.0, 4.0 * std::sqrt(3.125e-6 / static_cast<double>(left.size())));
  EXPECT_NEAR(sample_variance(left) / (0.005 * 0.005 * 0.125), 1.0, 0.12);
  const auto right = floor_errors(0.5, false);
  EXPECT_NEAR(sample_variance(right) / (0.01 * 0.01 * 0.125), 1.0, 0.12);
}

TEST(FloorNoise, VarianceGrowsInProportionToTravel) {
  // Four times the travel per sample → four times the variance.
  const double slow = sample_variance(floor_errors(0.125, false));
  const double fast = sample_variance(floor_errors(0.5, false));
  EXPECT_NEAR(fast / slow, 4.0, 4.0 * 0.2);
  EXPECT_NEAR(slow / (0.01 * 0.01 * 0.03125), 1.0, 0.12);
}

}  // namespace
}  // namespace locbench::sim
