#include "core/trajectory.h"

#include <gtest/gtest.h>

#include "tests/core/pose_matchers.h"

namespace locbench {
namespace {
using testing::IsNearlyPose;

TEST(Trajectory, InterpolatesPositionLinearlyAndHeadingAcrossPi) {
  const Trajectory t({{0.0, Pose2(0, 0, deg(170))}, {2.0, Pose2(2, 4, deg(-170))}});
  EXPECT_THAT(*t.pose_at(1.0), IsNearlyPose(Pose2(1, 2, deg(180)), 1e-12));
  EXPECT_THAT(*t.pose_at(0.5), IsNearlyPose(Pose2(0.5, 1, deg(175)), 1e-12));
}

TEST(Trajectory, HasNoPoseOutsideItsTimeSpan) {
  const Trajectory t({{1.0, Pose2()}, {2.0, Pose2(1, 0, 0)}});
  EXPECT_FALSE(t.pose_at(0.99));
  EXPECT_FALSE(t.pose_at(2.01));
  EXPECT_TRUE(t.pose_at(2.0));
}

TEST(Trajectory, RejectsTimeGoingBackwards) {
  EXPECT_THROW(Trajectory({{1.0, Pose2()}, {0.5, Pose2()}}), std::invalid_argument);
}

TEST(Trajectory, PathLengthSumsTheLegs) {
  const Trajectory t({{0, Pose2(0, 0, 0)}, {1, Pose2(3, 4, 0)}, {2, Pose2(3, 0, 0)}});
  EXPECT_DOUBLE_EQ(t.path_length(), 9.0);
}

}  // namespace
}  // namespace locbench
