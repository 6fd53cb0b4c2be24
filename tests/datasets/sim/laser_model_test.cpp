// Laser: 181 beams over ±90°, ray-cast ranges, systematic offset and scale, σ, dropouts,
// spurious returns, mounting pose.
#include "datasets/sim/laser_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/statistics.h"
#include "datasets/sim/worlds.h"
#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

class LaserModelTest : public ::testing::Test {
 protected:
  LaserConfig config() const {
    LaserConfig c;
    c.timing.enabled = true;
    return c;
  }
  // In a 1.8 m corridor at (3, 0.2) facing +x: beam at bearing b (0 < b < π) meets the wall
  // y = 0.9 at (0.9 − 0.2)/sin b, beams with b < 0 the wall y = −0.9 at 1.1/|sin b|.
  static double analytic(double b) {
    if (b > 0.0) return std::min(0.7 / std::sin(b), b < kPi / 2 ? 9.0 / std::cos(b) : 1e9);
    if (b < 0.0) return std::min(1.1 / std::sin(-b), 9.0 / std::cos(b));
    return 9.0;  // end wall at x = 12
  }
  // The noise-free ranges at pose_ under the default config (no random numbers involved).
  std::vector<double> true_ranges() const { return LaserModel(config(), world_, Rng(1)).true_ranges(pose_); }
  // Calls f(measured, true range) for every beam of `scans` scans from pose_ with the laser `c`.
  template <class F>
  void for_each_beam(const LaserConfig& c, std::uint64_t seed, int scans, F f) const {
    LaserModel m(c, world_, Rng(seed));
    const auto truth = true_ranges();
    for (int k = 0; k < scans; ++k) {
      const Scan s = m.measure(pose_, 0.0);
      for (std::size_t i = 0; i < s.ranges.size(); ++i) f(s.ranges[i], truth[i]);
    }
  }
  LineMap world_ = corridor_world(12.0, 1.8);
  Pose2 pose_{3.0, 0.2, 0.0};
};

TEST_F(LaserModelTest, Has181BeamsFromMinus90To90Degrees) {
  LaserModel m(config(), world_, Rng(1));
  ASSERT_EQ(m.bearings().size(), 181u);
  EXPECT_DOUBLE_EQ(m.bearings().front(), deg(-90.0));
  EXPECT_DOUBLE_EQ(m.bearings().back(), deg(90.0));
  EXPECT_NEAR(m.bearings()[1] - m.bearings()[0], deg(1.0), 1e-12);
  const Scan s = m.measure(pose_, 1.5);
  EXPECT_EQ(s.ranges.size(), 181u);
  EXPECT_EQ(s.timestamp, 1.5);
}

TEST_F(LaserModelTest, WithoutNoiseEachRangeIsTheDistanceToTheWall) {
  LaserConfig c = config();
  c.max_range = 20.0;
  LaserModel m(c, world_, Rng(1));
  const Scan s = m.measure(pose_, 0.0);
  for (std::size_t i = 0; i < s.ranges.size(); ++i) {
    EXPECT_NEAR(s.ranges[i], analytic(s.bearings[i]), 1e-9) << to_deg(s.bearings[i]);
  }
  EXPECT_NEAR(s.ranges[90], 9.0, 1e-12);   // straight ahead: the end wall
  EXPECT_NEAR(s.ranges[180], 0.7, 1e-12);  // left: y = 0.9
  EXPECT_NEAR(s.ranges[0], 1.1, 1e-12);    // right: y = −0.9
}

TEST_F(LaserModelTest, BeyondMaxRangeReadsMaxRange) {
  LaserModel m(config(), world_, Rng(1));  // 8 m: the end wall 9 m away is out of range
  const Scan s = m.measure(pose_, 0.0);
  EXPECT_EQ(s.ranges[90], 8.0);
  EXPECT_FALSE(s.valid(90));
  EXPECT_TRUE(s.valid(180));
}

TEST_F(LaserModelTest, OffsetAndScaleShiftRangesAsConfigured) {
  LaserConfig c = config();
  c.range_offset = 0.015;
  c.range_scale = 1.01;
  LaserModel m(c, world_, Rng(1));
  const Scan s = m.measure(pose_, 0.0);
  EXPECT_NEAR(s.ranges[180], 1.01 * 0.7 + 0.015, 1e-12);
  EXPECT_NEAR(s.ranges[0], 1.01 * 1.1 + 0.015, 1e-12);
}

TEST_F(LaserModelTest, RangeNoiseHasTheConfiguredSigma) {
  LaserConfig c = config();
  c.noise = 0.005;
  std::vector<double> err;
  for_each_beam(c, 9, 50, [&](double range, double truth) {
    if (truth < c.max_range) err.push_back(range - truth);
  });
  ASSERT_GT(err.size(), 8000u);
  EXPECT_NEAR(mean(err), 0.0, 0.0003);
  EXPECT_NEAR(sample_stddev(err), 0.005, 0.0002);  // σ measured ≈ 5 mm (±4%)
}

TEST_F(LaserModelTest, DropoutsOccurAtTheConfiguredRate) {
  LaserConfig c = config();
  c.dropout = 0.1;
  int dropped = 0, hits = 0;
  for_each_beam(c, 2, 100, [&](double range, double truth) {
    if (truth >= c.max_range) return;  // no return anyway
    ++hits;
    dropped += range == c.max_range;
  });
  // ~17000 beams, binomial standard error 0.0023.
  EXPECT_NEAR(static_cast<double>(dropped) / hits, 0.1, 0.01);
}

TEST_F(LaserModelTest, SpuriousReturnsAreShorterThanTheWall) {
  LaserConfig c = config();
  c.spurious = 0.2;
  int shorter = 0, total = 0;
  for_each_beam(c, 4, 100, [&](double range, double truth) {
    EXPECT_LE(range, truth);
    ++total;
    shorter += range < truth;
  });
  EXPECT_NEAR(static_cast<double>(shorter) / total, 0.2, 0.015);
}

TEST_F(LaserModelTest, RaysStartAtTheMountingPose) {
  LaserConfig c = config();
  c.mount = Pose2(0.2, 0.1, kPi / 2);  // 20 cm ahead, 10 cm left, looking left
  LaserModel m(c, world_, Rng(1));
  const Scan s = m.measure(pose_, 0.0);
  // Bearing 0 of the sensor looks along world +y from y = 0.3: the wall is 0.6 m away.
  EXPECT_NEAR(s.ranges[90], 0.6, 1e-12);
  EXPECT_EQ(s.sensor_pose.y, 0.1);
}

TEST(LaserInSimulation, ScansAt5HzWithTheOdometryPoseAndLatency) {
  Scenario s = preset("room_laser");
  s.laser.timing.latency = 0.02;
  const auto r = simulate(s, 1);
  ASSERT_GT(r.log.laser.size(), 250u);
  EXPECT_NEAR(r.log.laser[1].scan.timestamp - r.log.laser[0].scan.timestamp, 0.2, 1e-12);
  EXPECT_NEAR(r.log.laser[0].scan.timestamp, 0.02, 1e-12);
  EXPECT_NEAR(r.log.laser[0].pose.theta, deg(46.0), 1e-12);
  EXPECT_EQ(r.log.laser[0].scan.ranges.size(), 181u);
}

TEST_F(LaserModelTest, LabelledScanNamesTheSegmentEachBeamHitAndNothingForDropouts) {
  LaserConfig c = config();
  c.noise = 0.005;
  c.dropout = 0.2;
  LaserModel m(c, world_, Rng(3));
  LaserModel same(c, world_, Rng(3));
  const LabelledScan l = m.measure_labelled(Pose2(3.0, 0.2, 0.0), 1.0);
  const Scan s = same.measure(Pose2(3.0, 0.2, 0.0), 1.0);
  ASSERT_EQ(l.segment.size(), l.scan.ranges.size());
  EXPECT_EQ(l.scan.ranges, s.ranges);  // the same draws as measure()
  int dropped = 0;
  for (std::size_t i = 0; i < l.segment.size(); ++i) {
    if (l.scan.ranges[i] >= c.max_range) {
      EXPECT_EQ(l.segment[i], LabelledScan::kNoSegment);
      ++dropped;
      continue;
    }
    ASSERT_GE(l.segment[i], 0);
    // The labelled segment is the one the beam's end point lies on (within the noise).
    const Eigen::Vector2d p(3.0 + l.scan.ranges[i] * std::cos(l.scan.bearings[i]),
                            0.2 + l.scan.ranges[i] * std::sin(l.scan.bearings[i]));
    EXPECT_LT(distance_to_segment(world_.segments[static_cast<std::size_t>(l.segment[i])], p), 0.03);
  }
  EXPECT_GT(dropped, 20);  // ~36 of 181
}

}  // namespace
}  // namespace locbench::sim
