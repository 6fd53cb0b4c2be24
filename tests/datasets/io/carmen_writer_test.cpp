#include "datasets/io/carmen_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "datasets/io/carmen_laser.h"
#include "datasets/io/carmen_reader.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::log_difference;
using testing::ScratchDir;

LaserReading scan_at(double t, std::size_t n, double max_range = kDefaultFlaserMaxRange) {
  LaserReading r;
  r.scan.timestamp = t;
  r.scan.ranges.assign(n, 1.5);
  r.scan.bearings = flaser_bearings(n);
  r.scan.max_range = max_range;
  return r;
}

Log small_log() {
  Log log;
  log.params["robot_wheelbase"] = "0.5";
  log.encoders.push_back({2.0, -3, 4});
  log.odometry.push_back({1.0, Pose2(0.1, 0.2, 0.3), 0.5, -0.25});
  log.compass.push_back({2.0, 1.25});
  log.truth.push_back({1.5, Pose2(1, 2, 3), Pose2(4, 5, -1)});
  log.laser.push_back(scan_at(2.0, 3));
  return log;
}

TEST(CarmenWriter, WritesParamsFirstThenRecordsMergedInTimeOrderWithTiesByType) {
  const std::string text = format_carmen_log(small_log());
  const std::string expected =
      "# CARMEN log written by locbench; see datasets/FORMAT.md\n"
      "PARAM robot_wheelbase 0.5 0 locbench 0\n"
      "ODOM 0.1 0.2 0.3 0.5 -0.25 0 1 locbench 1\n"
      "TRUEPOS 1 2 3 4 5 -1 1.5 locbench 1.5\n"
      "ENCODER -3 4 2 locbench 2\n"
      "COMPASS 1.25 2 locbench 2\n"
      "FLASER 3 1.5 1.5 1.5 0 0 0 0 0 0 2 locbench 2\n";
  EXPECT_EQ(text, expected);
}

TEST(CarmenWriter, PrintsNumbersThatReadBackExactly) {
  Log log;
  log.odometry.push_back({976052857.337284, Pose2(0.1, 1.0 / 3.0, -2.0 / 3.0), 1e-300, -1e300});
  const std::string text = format_carmen_log(log);
  EXPECT_NE(text.find("976052857.337284 "), std::string::npos) << text;
  EXPECT_EQ(log_difference(log, parse_carmen_log(text, "m.clf")), "");
}

TEST(CarmenWriter, GzipsWhenThePathEndsInGz) {
  ScratchDir dir;
  write_carmen_log(small_log(), dir.file("a.clf.gz"));
  write_carmen_log(small_log(), dir.file("a.clf"));
  const std::string packed = testing::read_bytes(dir.file("a.clf.gz"));
  ASSERT_GE(packed.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(packed[0]), 0x1f);
  EXPECT_EQ(static_cast<unsigned char>(packed[1]), 0x8b);
  EXPECT_EQ(testing::read_bytes(dir.file("a.clf")), format_carmen_log(small_log()));
  EXPECT_EQ(log_difference(read_carmen_log(dir.file("a.clf.gz")), small_log()), "");
}

TEST(CarmenWriter, DeclaresTheScansMaxRangeAndMountingAsParams) {
  Log log;
  log.laser.push_back(scan_at(1.0, 5, 30.0));
  log.laser[0].scan.sensor_pose = Pose2(0.2, 0.0, 0.1);
  const Log back = parse_carmen_log(format_carmen_log(log), "m.clf");
  EXPECT_EQ(back.params.at(std::string(kParamLaserMaxRange)), "30");
  EXPECT_EQ(back.params.at(std::string(kParamLaserOffset)), "0.2");
  EXPECT_EQ(back.params.count(std::string(kParamLaserSideOffset)), 0u);  // 0 is the default
  EXPECT_EQ(back.laser[0].scan.max_range, 30.0);
  EXPECT_EQ(back.laser[0].scan.sensor_pose.theta, 0.1);
}

TEST(CarmenWriter, RejectsLogsTheFormatCannotHold) {
  auto rejects = [](const Log& log) { EXPECT_THROW(format_carmen_log(log), std::invalid_argument); };
  Log backwards = small_log();
  backwards.odometry.push_back({0.5, Pose2(), 0, 0});
  rejects(backwards);
  Log nan = small_log();
  nan.compass[0].heading = std::nan("");
  rejects(nan);
  Log negative = small_log();
  negative.laser[0].scan.ranges[1] = -1.0;
  rejects(negative);
  Log bearings = small_log();
  bearings.laser[0].scan.bearings[0] += 0.01;
  rejects(bearings);
  Log mixed = small_log();
  mixed.laser.push_back(scan_at(3.0, 3, 20.0));
  rejects(mixed);
  Log infinite = small_log();
  infinite.laser[0].scan.max_range = std::numeric_limits<double>::infinity();
  rejects(infinite);
  Log bad_param;  // would not read back
  bad_param.params[std::string(kParamRobotLaserMax)] = "-5";
  rejects(bad_param);
  Log spaced = small_log();
  spaced.params["world"] = "two words";
  rejects(spaced);
}

TEST(CarmenWriter, FailsWithInputErrorWhenTheFileCannotBeCreated) {
  ScratchDir dir;
  EXPECT_TRUE(testing::throws_input_error([&] { write_carmen_log(small_log(), dir.file("no/such/dir/a.clf")); },
                                          "a.clf", 0, {"cannot open for writing"}));
}

}  // namespace
}  // namespace locbench::io
