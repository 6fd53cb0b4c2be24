// The compass channel's parts on readings whose errors are known exactly: a robot driving along
// x at 0.5 m/s for 40 m while turning slowly, a compass at 5 Hz.
#include "algorithms/diagnosis/compass_channel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

namespace locbench::diagnosis {
namespace {

constexpr double kTurnRate = 0.01;  // [rad/s]

std::vector<TruePose> straight_run(double seconds) {
  std::vector<TruePose> truth;
  for (int k = 0; k <= static_cast<int>(seconds * 10.0); ++k) {
    const double t = 0.1 * k;
    const Pose2 p{0.5 * t, 0.0, kTurnRate * t};
    truth.push_back({t, p, p});
  }
  return truth;
}

// Readings at 5 Hz: true heading + bias + N(0, σ²), plus `zone_bias` while 18 m ≤ x ≤ 22 m.
CompassData readings(double bias, double sigma, double zone_bias, unsigned seed) {
  CompassData d;
  d.truth = straight_run(80.0);
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);  // scaled below: σ may be 0
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.2 * k, x = 0.5 * t;
    const double extra = x >= 18.0 && x <= 22.0 ? zone_bias : 0.0;
    d.readings.push_back({t, kTurnRate * t + bias + extra + sigma * n(rng)});
  }
  return d;
}

std::vector<std::size_t> all(const CompassData& d) {
  std::vector<std::size_t> i(d.readings.size());
  std::iota(i.begin(), i.end(), 0);
  return i;
}

TEST(CompassChannel, ResidualsAreTheReadingMinusTheInterpolatedTrueHeading) {
  const CompassData d = readings(0.05, 0.0, 0.0, 1);
  const auto r = compass_residuals(d, 0.0);
  ASSERT_EQ(r.size(), d.readings.size());
  for (const auto& x : r) {
    ASSERT_TRUE(x.valid);
    EXPECT_NEAR(x.r, 0.05, 1e-12);
    // The true turn rate is the heading change over ±0.05 s, 0 where that leaves the truth.
    if (x.t > 0.0 && x.t < 80.0) {
      EXPECT_NEAR(x.turn_rate, kTurnRate, 1e-9) << x.t;
    }
  }
  // With a 1 s offset the residual is the heading change over 1 s: 0.01 rad more.
  const auto shifted = compass_residuals(d, -1.0);
  EXPECT_NEAR(shifted[10].r, 0.05 - kTurnRate, 1e-12);
  // A reading beyond the truth's span has no residual.
  EXPECT_FALSE(compass_residuals(d, 1.0).front().valid);
}

TEST(CompassChannel, TheLikelihoodIsSmallestAtTheTrueBiasAndNoise) {
  const CompassData d = readings(0.05, 0.01, 0.0, 2);
  const auto i = all(d);
  CompassModel truth;
  truth.bias = 0.05;
  truth.sigma = 0.01;
  CompassModel no_bias = truth;
  no_bias.bias = 0.0;
  CompassModel wide = truth;
  wide.sigma = 0.03;
  EXPECT_LT(compass_nll(d, truth, i), compass_nll(d, no_bias, i) - 100.0);
  EXPECT_LT(compass_nll(d, truth, i), compass_nll(d, wide, i));
}

TEST(CompassChannel, TheBestZoneIsTheDiscWhereTheReadingsCarryAnExtraBias) {
  const CompassData d = readings(0.0, 0.005, 0.1, 3);
  CompassModel m;
  m.sigma = 0.005;
  const CompassZone z = best_compass_zone(d, m, all(d));
  ASSERT_TRUE(z.enabled);
  EXPECT_NEAR(z.x, 20.0, 1.0);
  EXPECT_NEAR(z.y, 0.0, 1.0);
  EXPECT_NEAR(z.radius, 2.0, 1.0);
  EXPECT_NEAR(z.bias, 0.1, 0.01);
  EXPECT_GT(z.candidates, 10u);
}

TEST(CompassChannel, FewerThanFortyOverlappingReadingsGiveAnEmptyChannel) {
  MotionData d;
  d.reference = ReferenceKind::kTruePose;
  d.truth = straight_run(80.0);
  for (int k = 0; k < 30; ++k) d.compass.push_back({0.2 * k, kTurnRate * 0.2 * k});
  const ChannelResult r = diagnose_compass(d, DiagnosisOptions{});
  EXPECT_TRUE(r.tests.empty());
  EXPECT_TRUE(r.causes.empty());
}

}  // namespace
}  // namespace locbench::diagnosis
