#include "core/pose2.h"

#include <gtest/gtest.h>

#include "tests/core/pose_matchers.h"

namespace locbench {
namespace {
using testing::IsNearlyPose;

TEST(Pose2, ComposeAppliesTheSecondMotionInTheFirstFrame) {
  const Pose2 a(1.0, 2.0, deg(90));
  const Pose2 b(1.0, 0.0, deg(90));
  EXPECT_THAT(a * b, IsNearlyPose(Pose2(1.0, 3.0, deg(180)), 1e-12));
}

TEST(Pose2, InverseUndoesCompose) {
  const Pose2 a(0.3, -1.2, deg(137));
  EXPECT_THAT(a * a.inverse(), IsNearlyPose(Pose2(), 1e-12));
  EXPECT_THAT(a.inverse() * a, IsNearlyPose(Pose2(), 1e-12));
}

TEST(Pose2, BetweenGivesTheMotionInTheFirstFrame) {
  const Pose2 a(1.0, 1.0, deg(90));
  const Pose2 b(1.0, 3.0, deg(90));
  EXPECT_THAT(between(a, b), IsNearlyPose(Pose2(2.0, 0.0, 0.0), 1e-12));
  EXPECT_THAT(a * between(a, b), IsNearlyPose(b, 1e-12));
}

TEST(Pose2, ConstructorWrapsTheHeading) { EXPECT_NEAR(Pose2(0, 0, deg(270)).theta, deg(-90), 1e-12); }

TEST(Pose2, MapsPointsToTheParentFrame) {
  const Pose2 a(2.0, 1.0, deg(90));
  const Eigen::Vector2d p = a * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), 2.0, 1e-12);
  EXPECT_NEAR(p.y(), 2.0, 1e-12);
}

}  // namespace
}  // namespace locbench
