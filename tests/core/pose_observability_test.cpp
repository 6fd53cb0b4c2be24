#include "core/pose_observability.h"

#include <gtest/gtest.h>

#include <cmath>

namespace locbench {
namespace {

TEST(PoseObservability, ScalesHeadingByTheLengthAndFlagsWeakDirections) {
  // H = diag(4, 1e-6, 9): θ scaled by 1/length = 1/3 gives diag(4, 1e-6, 1), sorted ascending.
  const Eigen::Matrix3d h = Eigen::Vector3d(4.0, 1e-6, 9.0).asDiagonal();
  const PoseObservability o = pose_observability(h, 3.0, 1e-3);
  EXPECT_NEAR(o.values(0), 1e-6, 1e-15);
  EXPECT_NEAR(o.values(1), 1.0, 1e-12);
  EXPECT_NEAR(o.values(2), 4.0, 1e-12);
  EXPECT_FALSE(o.observable[0]);  // 1e-6 < 1e-3 × 4
  EXPECT_TRUE(o.observable[1]);
  EXPECT_TRUE(o.observable[2]);
  EXPECT_TRUE(o.degenerate);
  EXPECT_NEAR(std::abs(o.vectors(1, 0)), 1.0, 1e-12);  // the weak direction is y
  EXPECT_DOUBLE_EQ(o.scale(2, 2), 1.0 / 3.0);
}

TEST(PoseObservability, AWellConditionedSystemIsNotDegenerateAndAZeroOneIs) {
  EXPECT_FALSE(pose_observability(Eigen::Matrix3d::Identity(), 1.0, 1e-3).degenerate);
  EXPECT_TRUE(pose_observability(Eigen::Matrix3d::Zero(), 1.0, 1e-3).degenerate);
}

}  // namespace
}  // namespace locbench
