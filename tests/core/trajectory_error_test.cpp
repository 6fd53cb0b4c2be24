#include "core/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace locbench {
namespace {

TEST(ErrorStatistics, UsesEvosVocabulary) {
  const std::vector<double> e{3, 4};
  const ErrorStatistics s = error_statistics(e);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(12.5));
  EXPECT_DOUBLE_EQ(s.mean, 3.5);
  EXPECT_DOUBLE_EQ(s.std, 0.5);
  EXPECT_DOUBLE_EQ(s.sse, 25.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

TEST(AbsolutePoseError, FirstPoseAlignmentRemovesAConstantOffset) {
  const Trajectory ref({{0, Pose2(1, 1, deg(90))}, {1, Pose2(1, 2, deg(90))}});
  const Trajectory est({{0, Pose2(0, 0, 0)}, {1, Pose2(1.1, 0, 0)}});
  const PoseErrors none = absolute_pose_error(ref, est, Alignment::kNone);
  EXPECT_NEAR(none.translation[0], std::sqrt(2.0), 1e-12);
  const PoseErrors first = absolute_pose_error(ref, est, Alignment::kFirstPose);
  EXPECT_NEAR(first.translation[0], 0.0, 1e-12);
  EXPECT_NEAR(first.translation[1], 0.1, 1e-12);
  EXPECT_NEAR(first.rotation[1], 0.0, 1e-12);
}

TEST(RelationError, ComparesRelativeMotionsAndSkipsRelationsOutsideTheEstimate) {
  const Trajectory est({{0, Pose2(0, 0, 0)}, {1, Pose2(1.0, 0, deg(10))}});
  const std::vector<Relation> rel{{0, 1, Pose2(1.0, 0.0, 0.0)}, {0, 5, Pose2()}};
  const PoseErrors e = relation_error(est, rel);
  ASSERT_EQ(e.translation.size(), 1u);
  EXPECT_NEAR(e.translation[0], 0.0, 1e-12);
  EXPECT_NEAR(e.rotation[0], deg(10), 1e-12);
}

}  // namespace
}  // namespace locbench
