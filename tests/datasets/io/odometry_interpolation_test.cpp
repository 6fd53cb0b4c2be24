#include "datasets/io/odometry_interpolation.h"

#include <gtest/gtest.h>

#include "core/units.h"

namespace locbench::io {
namespace {

Log two_odom(double th0, double th1) {
  Log log;
  log.odometry.push_back({10.0, Pose2(0, 0, th0), 0, 0});
  log.odometry.push_back({12.0, Pose2(2, -4, th1), 0, 0});
  return log;
}

TEST(OdometryInterpolation, InterpolatesPositionLinearlyInTime) {
  const auto p = interpolate_odometry(two_odom(0.0, 0.4), 10.5);
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->x, 0.5);
  EXPECT_DOUBLE_EQ(p->y, -1.0);
  EXPECT_DOUBLE_EQ(p->theta, 0.1);
}

TEST(OdometryInterpolation, InterpolatesHeadingAlongTheShorterArcAcrossPi) {
  const auto p = interpolate_odometry(two_odom(deg(170), deg(-170)), 11.0);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(std::abs(p->theta), kPi, 1e-12);  // through 180°, not through 0°
}

TEST(OdometryInterpolation, ReturnsRecordPosesAtTheirTimesAndNothingOutside) {
  const Log log = two_odom(0.0, 0.4);
  EXPECT_DOUBLE_EQ(interpolate_odometry(log, 10.0)->x, 0.0);
  EXPECT_DOUBLE_EQ(interpolate_odometry(log, 12.0)->y, -4.0);
  EXPECT_FALSE(interpolate_odometry(log, 9.99).has_value());
  EXPECT_FALSE(interpolate_odometry(log, 12.01).has_value());
  EXPECT_FALSE(interpolate_odometry(Log{}, 1.0).has_value());
}

TEST(OdometryInterpolation, FallsBackToFlaserOdomPosesWithoutOdomRecords) {
  Log log;
  LaserReading a, b;
  a.scan.timestamp = 1.0;
  a.odom_pose = Pose2(0, 0, 0);
  b.scan.timestamp = 3.0;
  b.odom_pose = Pose2(4, 0, 0);
  log.laser = {a, b};
  EXPECT_DOUBLE_EQ(interpolate_odometry(log, 2.0)->x, 2.0);
  EXPECT_EQ(odometry_trajectory(log).size(), 2u);
}

TEST(OdometryInterpolation, InterpolatesGroundTruth) {
  Log log;
  log.truth.push_back({0.0, Pose2(0, 0, 0), Pose2()});
  log.truth.push_back({1.0, Pose2(1, 1, 1), Pose2()});
  EXPECT_DOUBLE_EQ(interpolate_truth(log, 0.25)->y, 0.25);
}

}  // namespace
}  // namespace locbench::io
