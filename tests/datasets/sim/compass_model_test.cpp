// Compass: resolution, white noise, constant bias and disturbance zones.
#include "datasets/sim/compass_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/statistics.h"
#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

TEST(Quantize, RoundsToTheNearestMultiple) {
  EXPECT_DOUBLE_EQ(quantize(deg(2.9), deg(2.0)), deg(2.0));
  EXPECT_DOUBLE_EQ(quantize(deg(3.1), deg(2.0)), deg(4.0));
  EXPECT_DOUBLE_EQ(quantize(deg(-0.9), deg(2.0)), 0.0);
  EXPECT_DOUBLE_EQ(quantize(0.123, 0.0), 0.123);
}

TEST(CompassModel, WithTwoDegreeResolutionReportsOnlyMultiplesOfTwoDegrees) {
  CompassConfig c;
  c.resolution = deg(2.0);
  c.noise = deg(1.0);
  CompassModel m(c, Rng(3));
  for (int i = 0; i < 3600; ++i) {
    const double h = m.measure(Pose2(0.0, 0.0, deg(0.1 * i - 180.0))).heading;
    const double k = to_deg(h) / 2.0;
    EXPECT_NEAR(k, std::round(k), 1e-9) << to_deg(h);
    EXPECT_GE(h, -kPi);
    EXPECT_LT(h, kPi);
  }
}

TEST(CompassModel, BiasShiftsTheMeanReading) {
  CompassConfig c;
  c.noise = deg(1.5);
  c.bias = deg(3.0);
  CompassModel m(c, Rng(4));
  std::vector<double> err;
  for (int i = 0; i < 4000; ++i) err.push_back(m.measure(Pose2(1.0, 2.0, 0.5)).heading - 0.5);
  // Standard error 1.5°/√4000 = 0.024°.
  EXPECT_NEAR(to_deg(mean(err)), 3.0, 0.1);
  EXPECT_NEAR(to_deg(sample_stddev(err)), 1.5, 0.06);
}

TEST(CompassModel, DisturbanceZonesBiasReadingsOnlyInsideThem) {
  CompassConfig c;
  DisturbanceZone rect;
  rect.min = {2.0, -1.0};
  rect.max = {4.0, 1.0};
  rect.bias = deg(10.0);
  DisturbanceZone circle;
  circle.shape = DisturbanceZone::Shape::kCircle;
  circle.center = {8.0, 0.0};
  circle.radius = 0.5;
  circle.bias = deg(-7.0);
  c.zones = {rect, circle};
  CompassModel m(c, Rng(1));
  EXPECT_DOUBLE_EQ(m.measure(Pose2(1.9, 0.0, 0.2)).heading, 0.2);
  EXPECT_DOUBLE_EQ(m.measure(Pose2(3.0, 0.5, 0.2)).heading, 0.2 + deg(10.0));
  EXPECT_DOUBLE_EQ(m.measure(Pose2(8.3, 0.3, 0.2)).heading, 0.2 - deg(7.0));
  EXPECT_DOUBLE_EQ(m.measure(Pose2(8.3, 0.5, 0.2)).heading, 0.2);
  EXPECT_DOUBLE_EQ(m.measure(Pose2(3.0, 0.5, 0.2)).disturbance, deg(10.0));
}

TEST(CompassInSimulation, ZoneOnTheCorridorBiasesOnlyTheReadingsTakenInside) {
  Scenario s = testing::quiet_straight(10.0);
  DisturbanceZone z;
  z.min = {4.01, -1.0};  // edges between samples (every 25 mm)
  z.max = {6.01, 1.0};
  z.bias = deg(20.0);
  s.compass.zones = {z};
  const auto r = simulate(s, 1);
  ASSERT_EQ(r.log.compass.size(), r.log.truth.size());
  int inside = 0;
  for (std::size_t i = 0; i < r.log.compass.size(); ++i) {
    const double x = r.log.truth[i].pose.x;
    const double err = angle_diff(r.log.compass[i].heading, r.log.truth[i].pose.theta);
    if (x > 4.01 && x < 6.01) {
      EXPECT_NEAR(err, deg(20.0), 1e-12) << x;
      EXPECT_DOUBLE_EQ(r.compass_truth[i].disturbance, deg(20.0));
      ++inside;
    } else {
      EXPECT_NEAR(err, 0.0, 1e-12) << x;
    }
  }
  EXPECT_EQ(inside, 80);  // x = 4.025 … 6.000: 2 m at 0.25 m/s, 10 Hz
}

}  // namespace
}  // namespace locbench::sim
