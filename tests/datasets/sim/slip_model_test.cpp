// Wheel slip (§3.2): at most one wheel per encoder sample, at the configured rate, and every
// true event recorded with the travel it lost.
#include "datasets/sim/slip_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

TEST(SlipModel, NeverSlipsWhileStandingStill) {
  SlipModel m(SlipConfig{SlipRateUnit::kPerSample, {1.0, 0.1, 0.2}, {1.0, 0.1, 0.2}}, Rng(1));
  EXPECT_EQ(m.probability(MotionPhase::kIdle, 0.0, 0.25), 0.0);
  EXPECT_FALSE(m.start_interval(MotionPhase::kIdle, 0.0, 0.25).has_value());
}

TEST(SlipModel, PerMetreRateTurnsIntoAProbabilityPerInterval) {
  SlipModel m(SlipConfig{SlipRateUnit::kPerMetre, {0.4, 0.1, 0.2}, {2.0, 0.1, 0.2}}, Rng(1));
  // 0.25 m/s for 0.25 s = 62.5 mm: p = 1 − exp(−0.4 · 0.0625).
  EXPECT_DOUBLE_EQ(m.probability(MotionPhase::kStraight, 0.25, 0.25), 1.0 - std::exp(-0.025));
  EXPECT_DOUBLE_EQ(m.probability(MotionPhase::kTurn, 0.25, 0.25), 1.0 - std::exp(-0.125));
}

TEST(SlipModel, DrawsTheMagnitudeWithinItsRangeAndBothWheels) {
  SlipModel m(SlipConfig{SlipRateUnit::kPerSample, {1.0, 0.2, 0.3}, {}}, Rng(5));
  int left = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto s = m.start_interval(MotionPhase::kStraight, 0.25, 0.25);
    ASSERT_TRUE(s.has_value());
    EXPECT_GE(s->fraction, 0.2);
    EXPECT_LE(s->fraction, 0.3);
    left += s->wheel == Side::kLeft;
  }
  EXPECT_NEAR(left / 2000.0, 0.5, 0.05);
}

// The Trilobot running straight for 100 m (1600 samples at 4 Hz) with only slip enabled.
SimulationResult slipping_run(SlipConfig slip, double distance = 100.0) {
  Scenario s = preset("corridor");
  s.world.kind = WorldKind::kNone;
  s.motion.distance = distance;
  s.floor = FloorNoiseConfig{};
  s.slip = slip;
  return simulate(s, 11);
}

TEST(SlipInSimulation, HappensAtTheConfiguredRatePerSample) {
  const auto r = slipping_run({SlipRateUnit::kPerSample, {0.2, 0.3, 0.3}, {}});
  const double intervals = static_cast<double>(r.wheel_samples.size() - 1);
  const double rate = static_cast<double>(r.slips.size()) / intervals;
  // Binomial standard error sqrt(0.2 · 0.8 / 1600) = 0.01; the final pause adds idle intervals.
  EXPECT_NEAR(rate, 0.2, 0.035);
  for (const auto& e : r.slips) EXPECT_EQ(e.phase, MotionPhase::kStraight);
}

TEST(SlipInSimulation, HappensAtTheConfiguredRatePerMetre) {
  const auto r = slipping_run({SlipRateUnit::kPerMetre, {0.5, 0.3, 0.3}, {}}, 200.0);
  // 200 m × 0.5 per metre ≈ 100 events (Poisson: ± 10).
  EXPECT_NEAR(static_cast<double>(r.slips.size()), 100.0, 30.0);
}

TEST(SlipInSimulation, AffectsOnlyOneWheelPerSample) {
  const auto r = slipping_run({SlipRateUnit::kPerSample, {0.5, 0.1, 0.3}, {}});
  std::set<std::size_t> samples;
  for (const auto& e : r.slips) EXPECT_TRUE(samples.insert(e.sample).second) << e.sample;
  // The wheel not recorded as slipping lost nothing in that sample.
  const auto& w = r.wheel_samples;
  for (const auto& e : r.slips) {
    const auto& a = w[e.sample];
    const auto& b = w[e.sample + 1];
    const double other = e.wheel == Side::kLeft ? b.slip_right - a.slip_right : b.slip_left - a.slip_left;
    EXPECT_EQ(other, 0.0);
  }
}

TEST(SlipInSimulation, RecordsTheTravelEachEventLost) {
  const auto r = slipping_run({SlipRateUnit::kPerSample, {0.2, 0.1, 0.3}, {}});
  ASSERT_GT(r.slips.size(), 100u);
  const auto& w = r.wheel_samples;
  for (const auto& e : r.slips) {
    const auto& a = w[e.sample];
    const auto& b = w[e.sample + 1];
    EXPECT_DOUBLE_EQ(a.t, e.t_start);
    EXPECT_DOUBLE_EQ(b.t, e.t_end);
    const bool left = e.wheel == Side::kLeft;
    const double rim = left ? b.rim_left - a.rim_left : b.rim_right - a.rim_right;
    const double ground = left ? b.ground_left - a.ground_left : b.ground_right - a.ground_right;
    // Without floor noise the lost travel is exactly rim − ground = fraction × rim.
    // (Up to the rounding of sums over 100 m.)
    EXPECT_NEAR(e.lost, rim - ground, 1e-9);
    EXPECT_NEAR(e.lost, e.fraction * rim, 1e-9);
  }
  // Samples without an event lose nothing.
  double total = 0.0;
  for (const auto& e : r.slips) total += e.lost;
  EXPECT_NEAR(total, w.back().slip_left + w.back().slip_right, 1e-9);
}

TEST(SlipInSimulation, StraightAndTurnProfilesAreSeparate) {
  Scenario s = preset("umbmark_trilobot");
  s.motion.runs = 1;
  s.floor = FloorNoiseConfig{};
  s.slip = {SlipRateUnit::kPerSample, {0.0, 0.1, 0.2}, {0.6, 0.2, 0.2}};
  const auto r = simulate(s, 2);
  ASSERT_FALSE(r.slips.empty());
  for (const auto& e : r.slips) {
    EXPECT_EQ(e.phase, MotionPhase::kTurn);
    EXPECT_DOUBLE_EQ(e.fraction, 0.2);
  }
}

TEST(SlipInSimulation, DeflectsTheTrueHeadingTowardsTheSlippingWheel) {
  const auto r = slipping_run({SlipRateUnit::kPerSample, {0.2, 0.3, 0.3}, {}}, 10.0);
  ASSERT_FALSE(r.slips.empty());
  const auto& e = r.slips.front();
  const auto& w = r.wheel_samples;
  const double turn = angle_diff(w[e.sample + 1].pose.theta, w[e.sample].pose.theta);
  // A left wheel losing travel turns the robot left (counter-clockwise), and vice versa:
  // Δθ = (U_R − U_L)/B with the lost travel taken off one side (eq. 1.2).
  const double expected = (e.wheel == Side::kLeft ? 1.0 : -1.0) * e.lost / r.robot.actual.wheelbase;
  EXPECT_NEAR(turn, expected, 1e-3);
}

}  // namespace
}  // namespace locbench::sim
