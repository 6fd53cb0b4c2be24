#include "datasets/io/tum_writer.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "core/units.h"
#include "datasets/io/tum_reader.h"
#include "io_test_support.h"
#include "log_generators.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

TEST(TumWriter, WritesTimestampPositionZeroZAndYawQuaternion) {
  const Trajectory traj({{1.5, Pose2(1, 2, kPi / 2)}});
  const std::string text = format_tum(traj);
  EXPECT_EQ(text.substr(0, text.find('\n')), "# timestamp x y z qx qy qz qw");
  double t, x, y, z, qx, qy, qz, qw;
  ASSERT_EQ(std::sscanf(text.c_str() + text.find('\n') + 1, "%lf %lf %lf %lf %lf %lf %lf %lf", &t, &x, &y, &z, &qx, &qy,
                        &qz, &qw),
            8);
  EXPECT_EQ(t, 1.5);
  EXPECT_EQ(x, 1.0);
  EXPECT_EQ(y, 2.0);
  EXPECT_EQ(z, 0.0);
  EXPECT_EQ(qx, 0.0);
  EXPECT_EQ(qy, 0.0);
  EXPECT_NEAR(qz, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-15);
}

TEST(TumReader, ReadsYawFromAGeneralQuaternion) {
  // Yaw 0.5 rad composed with a small roll: the heading is still the yaw.
  const double h = 0.25, r = 0.05;
  const double qw = std::cos(h) * std::cos(r), qx = std::cos(h) * std::sin(r);
  const double qy = std::sin(h) * std::sin(r), qz = std::sin(h) * std::cos(r);
  const std::string line = fmt::format("3 1 2 0.5 {} {} {} {}\n", qx, qy, qz, qw);
  const Trajectory traj = parse_tum(line, "t.tum");
  ASSERT_EQ(traj.size(), 1u);
  EXPECT_NEAR(traj.poses()[0].pose.theta, 0.5, 1e-6);
}

TEST(TumReader, RejectsNonUnitQuaternionsAndBackwardsTime) {
  EXPECT_TRUE(testing::throws_input_error([] { parse_tum("1 0 0 0 0 0 0 0\n", "t.tum"); }, "t.tum", 1,
                                          {"expected a unit quaternion"}));
  EXPECT_TRUE(testing::throws_input_error([] { parse_tum("2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", "t.tum"); }, "t.tum", 2,
                                          {"goes back in time"}));
  EXPECT_TRUE(testing::throws_input_error([] { parse_tum("2 0 0 0 0 0 1\n", "t.tum"); }, "t.tum", 1,
                                          {"expected 8 fields, found 7"}));
}

RC_GTEST_PROP(TumRoundTrip, ReadingWhatWasWrittenGivesTheSameTrajectory, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(0, 30);
  std::vector<double> times;
  for (std::size_t i = 0; i < count; ++i) times.push_back(*testing::gen_finite());
  std::sort(times.begin(), times.end());
  std::vector<StampedPose> poses;
  for (const double t : times) poses.push_back({t, *testing::gen_pose()});
  const Trajectory traj(poses);
  const Trajectory back = parse_tum(format_tum(traj), "m.tum");
  RC_ASSERT(back.size() == traj.size());
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const auto& a = traj.poses()[i];
    const auto& b = back.poses()[i];
    RC_ASSERT(a.t == b.t);
    RC_ASSERT(a.pose.x == b.pose.x);
    RC_ASSERT(a.pose.y == b.pose.y);
    RC_ASSERT(std::abs(angle_diff(a.pose.theta, b.pose.theta)) <= 1e-12);  // via sin/cos/atan2
  }
}

TEST(TumRoundTrip, GzipFileRoundTrip) {
  testing::ScratchDir dir;
  const Trajectory traj({{0.0, Pose2(0, 0, 0)}, {0.5, Pose2(1, -1, -3.0)}, {1.0, Pose2(2, 0, 3.1)}});
  write_tum(traj, dir.file("t.tum.gz"));
  const Trajectory back = read_tum(dir.file("t.tum.gz"));
  ASSERT_EQ(back.size(), 3u);
  EXPECT_NEAR(back.poses()[1].pose.theta, -3.0, 1e-12);
  EXPECT_NEAR(back.poses()[2].pose.theta, 3.1, 1e-12);
}

}  // namespace
}  // namespace locbench::io
