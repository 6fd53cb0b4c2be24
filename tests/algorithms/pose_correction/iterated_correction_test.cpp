// EAP matches + iterated joint point-to-line solve: where one chapter-6 pass leaves an error,
// re-matching and solving jointly converge; parallel walls keep the along-wall estimate.
#include "algorithms/pose_correction/iterated_correction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"
#include "tests/algorithms/pose_correction/ray_cast_matches.h"

namespace locbench::pose_correction {
namespace {

const Pose2 kTruth{2.0, 1.0, deg(46.0)};  // §6.6.1
const Pose2 kEstimate{2.1, 1.1, deg(41.0)};

TEST(SolvePointToLine, NoiseFreeOracleMatchesGiveTheTruePoseExactly) {
  const LineMap room = sim::room_world();
  const auto matches = test::matches_by_true_hit(test::ray_cast_scan(room, kTruth), kEstimate);
  IteratedCorrectionOptions o;
  o.keep_fraction = 1.0;
  o.inner_steps = 10;
  const IteratedCorrection c = solve_point_to_line(matches, room, kEstimate, o);
  ASSERT_TRUE(c.valid);
  EXPECT_FALSE(c.degenerate);
  EXPECT_NEAR(c.corrected.x, kTruth.x, 1e-9);
  EXPECT_NEAR(c.corrected.y, kTruth.y, 1e-9);
  EXPECT_NEAR(angle_diff(c.corrected.theta, kTruth.theta), 0.0, 1e-9);
  EXPECT_LT(c.residual_rms, 1e-9);
}

TEST(IteratedPointToLine, ConvergesWhereOneChapter6PassFromEapMatchesDoesNot) {
  const LineMap room = sim::room_world();
  const laser::EapMatcher eap;
  double one_shot = 0.0, iterated = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Rng rng(seed);
    const Scan scan = test::ray_cast_scan(room, kTruth, &rng).scan;
    const auto m = eap.match(scan, room, kEstimate);
    const PoseCorrection c = correct_pose(m.matches, room, kEstimate);
    one_shot += translation_distance(c.corrected, kTruth) / 5;
    const IteratedCorrection it = iterated_point_to_line(eap, scan, room, kEstimate);
    ASSERT_TRUE(it.valid);
    EXPECT_TRUE(it.converged);
    EXPECT_GT(it.iterations, 1);
    EXPECT_LT(std::abs(angle_diff(it.corrected.theta, kTruth.theta)), deg(0.1));
    iterated += translation_distance(it.corrected, kTruth) / 5;
  }
  EXPECT_LT(iterated, 0.005);  // mm level
  EXPECT_LT(iterated, 0.5 * one_shot);
}

TEST(IteratedPointToLine, ParallelWallsFixHeadingAndAcrossButKeepTheAlongWallEstimate) {
  LineMap corridor;
  corridor.segments = {{{-15, -1}, {15, -1}}, {{-15, 1}, {15, 1}}};
  const Pose2 truth(0.0, 0.2, deg(3));
  const Pose2 estimate(0.3, 0.25, deg(5));
  Rng rng(4);
  const Scan scan = test::ray_cast_scan(corridor, truth, &rng).scan;
  const laser::EapMatcher eap;
  const IteratedCorrection c = iterated_point_to_line(eap, scan, corridor, estimate);
  ASSERT_TRUE(c.valid);
  EXPECT_TRUE(c.degenerate);
  EXPECT_NEAR(c.corrected.y, truth.y, 0.005);
  EXPECT_NEAR(angle_diff(c.corrected.theta, truth.theta), 0.0, deg(0.1));
  EXPECT_NEAR(c.corrected.x, estimate.x, 1e-9);
  EXPECT_TRUE(std::isinf(c.covariance(0, 0)));
}

TEST(IteratedPointToLine, NoMatchesLeavesTheEstimateAndOptionsAreStrict) {
  LineMap far;
  far.segments = {{{100, 100}, {101, 100}}};
  const Scan scan = test::ray_cast_scan(sim::room_world(), kTruth).scan;
  const IteratedCorrection c = iterated_point_to_line(laser::EapMatcher{}, scan, far, kEstimate);
  EXPECT_FALSE(c.valid);
  EXPECT_EQ(c.corrected.x, kEstimate.x);
  IteratedCorrectionOptions o;
  EXPECT_THROW(from_json(nlohmann::json{{"keep_fraction", 1.5}}, o), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"unknown", 1}}, o), UsageError);
  EXPECT_THROW(iterated_point_to_line(laser::EapMatcher{}, scan, far, Pose2(NAN, 0, 0)), UsageError);
}

}  // namespace
}  // namespace locbench::pose_correction
