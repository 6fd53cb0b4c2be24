#include "core/dead_reckoning.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/pose_matchers.h"

namespace locbench {
namespace {
using testing::IsNearlyPose;

TEST(DeadReckonEncoders, IntegratesTickIncrementsWithTheModel) {
  const NominalModel m{0.01, 0.01, 0.2};
  // 100 ticks straight, then a quarter turn on the spot (U = B π/4 = 0.05π m ≈ 15.708 ticks).
  const std::vector<EncoderReading> e{{0.0, 0, 0}, {1.0, 100, 100}, {2.0, 100 - 5, 100 + 5}};
  const Trajectory t = dead_reckon_encoders(e, m, Pose2(1, 1, 0));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_THAT(t.poses()[1].pose, IsNearlyPose(Pose2(2, 1, 0), 1e-12));
  EXPECT_THAT(t.poses()[2].pose, IsNearlyPose(Pose2(2, 1, 0.1 / 0.2), 1e-12));
}

TEST(DeadReckonVelocities, HoldsEachVelocityOverItsInterval) {
  const std::vector<OdometryReading> o{{0.0, {}, 1.0, 0.0}, {2.0, {}, 0.0, kPi / 2}, {3.0, {}, 0.0, 0.0}};
  const Trajectory t = dead_reckon_velocities(o, Pose2());
  EXPECT_THAT(t.poses()[1].pose, IsNearlyPose(Pose2(2, 0, 0), 1e-12));
  EXPECT_THAT(t.poses()[2].pose, IsNearlyPose(Pose2(2, 0, kPi / 2), 1e-12));
}

}  // namespace
}  // namespace locbench
