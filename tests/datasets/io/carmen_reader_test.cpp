#include "datasets/io/carmen_reader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.h"
#include "datasets/io/carmen_laser.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::gzip;
using testing::ScratchDir;
using testing::write_bytes;

std::string flaser_line(std::size_t n, double range, double t) {
  const std::string r = std::to_string(range), ts = std::to_string(t);
  std::string s = "FLASER ";
  s += std::to_string(n);
  for (std::size_t i = 0; i < n; ++i) s.append(" ").append(r);
  s.append(" 1 2 0.5 3 4 -0.5 ").append(ts).append(" host ").append(ts).append("\n");
  return s;
}

TEST(CarmenReader, ReadsOdomPoseVelocitiesAndTimestamp) {
  const Log log = parse_carmen_log("ODOM 1.5 -2 0.25 0.3 -0.1 0 12.5 robot 99\n", "a.clf");
  ASSERT_EQ(log.odometry.size(), 1u);
  const auto& r = log.odometry[0];
  EXPECT_EQ(r.t, 12.5);  // the IPC timestamp, not the logger timestamp
  EXPECT_EQ(r.pose.x, 1.5);
  EXPECT_EQ(r.pose.y, -2.0);
  EXPECT_EQ(r.pose.theta, 0.25);
  EXPECT_EQ(r.tv, 0.3);
  EXPECT_EQ(r.rv, -0.1);
  EXPECT_EQ(log.name, "a");
  EXPECT_EQ(log.source, "a.clf");
}

TEST(CarmenReader, WrapsHeadingsIntoMinusPiToPi) {
  const Log log = parse_carmen_log("ODOM 0 0 4 0 0 0 1 h 1\n", "a.clf");
  EXPECT_NEAR(log.odometry[0].pose.theta, 4.0 - 2.0 * kPi, 1e-15);
}

TEST(CarmenReader, FlaserWith181BeamsSpans180DegreesAtOneDegree) {
  const Log log = parse_carmen_log(flaser_line(181, 2.0, 5.0), "a.clf");
  ASSERT_EQ(log.laser.size(), 1u);
  const Scan& s = log.laser[0].scan;
  ASSERT_EQ(s.bearings.size(), 181u);
  EXPECT_DOUBLE_EQ(s.bearings.front(), -kPi / 2);
  EXPECT_DOUBLE_EQ(s.bearings[90], 0.0 - 0.0);
  EXPECT_DOUBLE_EQ(s.bearings.back(), kPi / 2);
  EXPECT_NEAR(s.bearings[1] - s.bearings[0], deg(1.0), 1e-12);
  EXPECT_EQ(s.timestamp, 5.0);
  EXPECT_EQ(s.ranges[0], 2.0);
  EXPECT_EQ(log.laser[0].pose.x, 1.0);
  EXPECT_EQ(log.laser[0].odom_pose.y, 4.0);
  EXPECT_EQ(log.laser[0].odom_pose.theta, -0.5);
}

TEST(CarmenReader, FlaserWith361BeamsHasHalfDegreeSteps) {
  const Scan s = parse_carmen_log(flaser_line(361, 2.0, 5.0), "a.clf").laser.at(0).scan;
  EXPECT_DOUBLE_EQ(s.bearings.front(), -kPi / 2);
  EXPECT_DOUBLE_EQ(s.bearings.back(), kPi / 2);
  EXPECT_NEAR(s.bearings[1] - s.bearings[0], deg(0.5), 1e-12);
}

TEST(CarmenReader, FlaserWith180BeamsRunsFromMinus90To89Degrees) {
  const Scan s = parse_carmen_log(flaser_line(180, 2.0, 5.0), "a.clf").laser.at(0).scan;
  EXPECT_DOUBLE_EQ(s.bearings.front(), -kPi / 2);
  EXPECT_NEAR(s.bearings.back(), deg(89.0), 1e-12);
  EXPECT_NEAR(s.bearings[1] - s.bearings[0], deg(1.0), 1e-12);
}

TEST(CarmenReader, FlaserAcceptsAnyPositiveBeamCount) {
  const Log log = parse_carmen_log(flaser_line(1, 2.0, 1.0) + flaser_line(7, 2.0, 2.0), "a.clf");
  ASSERT_EQ(log.laser.size(), 2u);
  EXPECT_EQ(log.laser[0].scan.bearings, std::vector<double>{-kPi / 2});
  EXPECT_EQ(log.laser[1].scan.ranges.size(), 7u);
  EXPECT_DOUBLE_EQ(log.laser[1].scan.bearings[3], 0.0);
}

TEST(CarmenReader, MaxRangeDefaultsToSickConventionSoThatSaturatedReadingsAreNoReturn) {
  const Scan s = parse_carmen_log(flaser_line(3, 81.91, 1.0), "a.clf").laser.at(0).scan;
  EXPECT_EQ(s.max_range, kDefaultFlaserMaxRange);
  EXPECT_FALSE(s.valid(0));
}

TEST(CarmenReader, MaxRangeComesFromLaserParam) {
  const Log log = parse_carmen_log(
      "PARAM laser_front_laser_max_range 50 0 h 0\nPARAM robot_front_laser_max 30\n" + flaser_line(3, 2.0, 1.0),
      "a.clf");
  EXPECT_EQ(log.laser[0].scan.max_range, 50.0);  // laser_front_laser_max_range wins
  const Log log2 = parse_carmen_log("PARAM robot_front_laser_max 30\n" + flaser_line(3, 2.0, 1.0), "b.clf");
  EXPECT_EQ(log2.laser[0].scan.max_range, 30.0);
}

TEST(CarmenReader, MaxRangeParamMayFollowTheScans) {
  const Log log = parse_carmen_log(flaser_line(3, 2.0, 1.0) + "PARAM robot_front_laser_max 30\n", "a.clf");
  EXPECT_EQ(log.laser[0].scan.max_range, 30.0);
}

TEST(CarmenReader, SensorPoseComesFromFrontLaserOffsetParams) {
  const Log log = parse_carmen_log(
      "PARAM robot_frontlaser_offset 0.2\nPARAM robot_frontlaser_side_offset -0.05\n"
      "PARAM robot_frontlaser_angular_offset 0.1\n" +
          flaser_line(3, 2.0, 1.0),
      "a.clf");
  const Pose2& p = log.laser[0].scan.sensor_pose;
  EXPECT_EQ(p.x, 0.2);
  EXPECT_EQ(p.y, -0.05);
  EXPECT_EQ(p.theta, 0.1);
}

TEST(CarmenReader, ParamAcceptsTwoFourAndFiveFieldForms) {
  const Log log = parse_carmen_log("PARAM a 1\nPARAM b two host 12.5\nPARAM c x_y 12.5 host 0.01\n", "a.clf");
  EXPECT_EQ(log.params.at("a"), "1");
  EXPECT_EQ(log.params.at("b"), "two");
  EXPECT_EQ(log.params.at("c"), "x_y");
}

TEST(CarmenReader, ReadsEncoderTicksAsSigned64BitCounts) {
  const Log log =
      parse_carmen_log("ENCODER -9223372036854775808 9223372036854775807 1.25 h 1.25\nENCODER -5 +7 2 h 2\n", "a.clf");
  ASSERT_EQ(log.encoders.size(), 2u);
  EXPECT_EQ(log.encoders[0].left, std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(log.encoders[0].right, std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(log.encoders[0].t, 1.25);
  EXPECT_EQ(log.encoders[1].left, -5);
  EXPECT_EQ(log.encoders[1].right, 7);
}

TEST(CarmenReader, ReadsCompassHeadingInRadians) {
  const Log log = parse_carmen_log("COMPASS 1.5 3 h 3\n", "a.clf");
  ASSERT_EQ(log.compass.size(), 1u);
  EXPECT_EQ(log.compass[0].heading, 1.5);
  EXPECT_EQ(log.compass[0].t, 3.0);
}

TEST(CarmenReader, ReadsTrueposWithItsOdometryPose) {
  const Log log = parse_carmen_log("TRUEPOS 1 2 0.3 4 5 0.6 7 h 7\n", "a.clf");
  ASSERT_EQ(log.truth.size(), 1u);
  EXPECT_EQ(log.truth[0].pose.y, 2.0);
  EXPECT_EQ(log.truth[0].odom_pose.theta, 0.6);
  EXPECT_EQ(log.truth[0].t, 7.0);
}

TEST(CarmenReader, SkipsCommentsAndBlankLinesAndCountsUnknownRecords) {
  const Log log = parse_carmen_log(
      "# header\n\n   \n  # indented comment\nSONAR 1 2 3\nROBOTLASER1 0 1 2\nSONAR 4\n"
      "ODOM 0 0 0 0 0 0 1 h 1\r\nNMEAGGA x\n",
      "a.clf");
  EXPECT_EQ(log.odometry.size(), 1u);
  const auto skipped = skipped_record_counts(log);
  EXPECT_EQ(skipped, (std::map<std::string, std::size_t>{{"NMEAGGA", 1}, {"ROBOTLASER1", 1}, {"SONAR", 2}}));
  EXPECT_EQ(log.params.at("locbench_skipped_records.SONAR"), "2");
}

TEST(CarmenReader, AcceptsEqualTimestampsAndIndependentOrderAcrossRecordTypes) {
  const Log log =
      parse_carmen_log("ODOM 0 0 0 0 0 0 5 h 5\nODOM 0 0 0 0 0 0 5 h 5\nCOMPASS 0 1 h 1\nENCODER 1 1 0 h 0\n", "a.clf");
  EXPECT_EQ(log.odometry.size(), 2u);
  EXPECT_EQ(log.compass.size(), 1u);
  EXPECT_EQ(log.encoders.size(), 1u);
}

TEST(CarmenReader, ReadsGzipAndPlainFilesAlike) {
  ScratchDir dir;
  const std::string text = "ODOM 1 2 0 0 0 0 1 h 1\n" + flaser_line(180, 3.0, 2.0);
  write_bytes(dir.file("x.clf"), text);
  write_bytes(dir.file("x.clf.gz"), gzip(text));
  const Log plain = read_carmen_log(dir.file("x.clf"));
  const Log packed = read_carmen_log(dir.file("x.clf.gz"));
  EXPECT_EQ(testing::log_difference(plain, packed), "");
  EXPECT_EQ(packed.name, "x");
  EXPECT_EQ(packed.source, dir.file("x.clf.gz").string());
}

TEST(CarmenReader, ReadsLastLineWithoutNewline) {
  const Log log = parse_carmen_log("ODOM 1 2 0 0 0 0 1 h 1\nODOM 1 2 0 0 0 0 2 h 2", "a.clf");
  EXPECT_EQ(log.odometry.size(), 2u);
}

}  // namespace
}  // namespace locbench::io
