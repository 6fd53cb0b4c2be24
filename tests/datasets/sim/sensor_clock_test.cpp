// Sensor timing: rates, jitter, and latency (logged time = true measurement time + latency).
#include "datasets/sim/sensor_clock.h"

#include <gtest/gtest.h>

#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

TEST(SensorClock, FiresAtMultiplesOfThePeriodInPhysicsSteps) {
  SensorClock c(SensorTiming{true, 4.0, 0.0, 0.0}, 1e-3, Rng(1));
  std::vector<std::int64_t> steps;
  for (int i = 0; i < 4; ++i) {
    steps.push_back(c.next_step());
    c.advance();
  }
  EXPECT_EQ(steps, (std::vector<std::int64_t>{0, 250, 500, 750}));
}

TEST(SensorClock, DisabledNeverFires) {
  SensorClock c(SensorTiming{false, 4.0, 0.0, 0.0}, 1e-3, Rng(1));
  EXPECT_FALSE(c.enabled());
  EXPECT_EQ(c.next_step(), std::numeric_limits<std::int64_t>::max());
}

TEST(SensorClock, JitterMovesInstantsButKeepsThemOrderedAndNearTheGrid) {
  SensorClock c(SensorTiming{true, 4.0, 0.0, 0.05}, 1e-3, Rng(2));
  std::int64_t previous = -1;
  double sum_sq = 0.0;
  const int n = 4000;
  for (int k = 0; k < n; ++k) {
    const std::int64_t s = c.next_step();
    EXPECT_GT(s, previous);
    EXPECT_LE(std::abs(s - 250 * k), 113);  // clipped to ±0.45 period
    if (k > 0) sum_sq += std::pow((s - 250.0 * k) * 1e-3, 2);
    previous = s;
    c.advance();
  }
  EXPECT_NEAR(std::sqrt(sum_sq / (n - 1)), 0.05, 0.003);
}

TEST(SensorLatency, ShiftsLoggedTimestampsByTheOffsetAndNothingElse) {
  Scenario s = preset("corridor");
  const auto base = simulate(s, 5);
  s.encoders.timing.latency = 0.1;
  s.compass.timing.latency = -0.03;
  const auto late = simulate(s, 5);
  ASSERT_EQ(base.log.encoders.size(), late.log.encoders.size());
  for (std::size_t i = 0; i < base.log.encoders.size(); ++i) {
    EXPECT_NEAR(late.log.encoders[i].t, base.log.encoders[i].t + 0.1, 1e-12);
    EXPECT_EQ(late.log.encoders[i].left, base.log.encoders[i].left);
    // The true measurement instant is unchanged.
    EXPECT_DOUBLE_EQ(late.wheel_samples[i].t, base.wheel_samples[i].t);
    EXPECT_NEAR(late.log.encoders[i].t - late.wheel_samples[i].t, 0.1, 1e-12);
  }
  ASSERT_EQ(base.log.compass.size(), late.log.compass.size());
  for (std::size_t i = 0; i < base.log.compass.size(); ++i) {
    EXPECT_NEAR(late.log.compass[i].t, base.log.compass[i].t - 0.03, 1e-12);
    EXPECT_EQ(late.log.compass[i].heading, base.log.compass[i].heading);
  }
  // Truth is never delayed.
  EXPECT_EQ(late.log.truth.front().t, 0.0);
}

TEST(SensorRates, EachSensorKeepsItsOwnRate) {
  const auto r = simulate(preset("room_laser"), 1);
  EXPECT_NEAR(r.log.encoders[1].t - r.log.encoders[0].t, 0.1, 1e-12);
  EXPECT_NEAR(r.log.odometry[1].t - r.log.odometry[0].t, 0.1, 1e-12);
  EXPECT_NEAR(r.log.laser[1].scan.timestamp - r.log.laser[0].scan.timestamp, 0.2, 1e-12);
  EXPECT_NEAR(r.trajectory[1].t - r.trajectory[0].t, 0.01, 1e-12);  // 100 Hz truth trajectory
}

}  // namespace
}  // namespace locbench::sim
