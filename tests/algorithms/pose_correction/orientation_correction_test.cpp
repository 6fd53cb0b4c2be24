#include "algorithms/pose_correction/orientation_correction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"
#include "tests/algorithms/pose_correction/ray_cast_matches.h"

namespace locbench::pose_correction {
namespace {

using Eigen::Vector2d;

// World points of the segment a→b as seen from `truth` but re-projected under `estimate`.
std::vector<Vector2d> seen_under(const Pose2& truth, const Pose2& estimate, const Vector2d& a, const Vector2d& b,
                                 int n) {
  std::vector<Vector2d> out;
  for (const auto& r : test::robot_points_on(truth, a, b, n)) out.push_back(estimate * r);
  return out;
}

TEST(SegmentOrientation, HorizontalWallGivesTheCorrectionToAddToTheEstimate) {
  // Estimate heading 5° too large: Δθ = θ_true − θ_est = −5°, y-on-x branch (6.3–6.5).
  const Pose2 truth{0.0, 0.0, 0.0}, estimate{0.0, 0.0, deg(5.0)};
  const Segment wall{{-3.0, 2.0}, {3.0, 2.0}};
  const auto pts = seen_under(truth, estimate, {-1.5, 2.0}, {2.5, 2.0}, 20);
  const SegmentOrientation s = segment_orientation(pts, wall, {});
  EXPECT_FALSE(s.near_vertical);
  EXPECT_NEAR(s.delta, deg(-5.0), 1e-12);
  EXPECT_NEAR(estimate.theta + s.delta, truth.theta, 1e-12);
}

TEST(SegmentOrientation, VerticalWallTakesTheRotatedBranchAndGivesTheRightSign) {
  // Map slope a = ∞: eq. 6.7–6.11 (centre, rotate −90°, refit, + 90°). Estimate 3° too small.
  const Pose2 truth{1.0, 1.0, deg(30.0)}, estimate{1.0, 1.0, deg(27.0)};
  const Segment wall{{4.0, -2.0}, {4.0, 5.0}};
  const auto pts = seen_under(truth, estimate, {4.0, -1.0}, {4.0, 3.0}, 30);
  const SegmentOrientation s = segment_orientation(pts, wall, {});
  EXPECT_TRUE(s.near_vertical);
  EXPECT_NEAR(s.delta, deg(3.0), 1e-12);
}

TEST(SegmentOrientation, NearVerticalBranchAvoidsTheYOnXAttenuationOfNoisyPoints) {
  // A vertical wall seen with a 0.5° heading error: the points' x spread is 2 m · sin 0.5° =
  // 17 mm, comparable to σ = 5 mm, so a y-on-x fit attenuates the slope and reports far less
  // than the true −0.5°; the rotated branch fits along y and is unaffected.
  const Pose2 truth{0.0, 0.0, 0.0}, estimate{0.0, 0.0, deg(0.5)};
  const Segment wall{{3.0, -2.0}, {3.0, 2.0}};
  Rng rng(7);
  std::vector<Vector2d> pts = seen_under(truth, estimate, {3.0, -1.0}, {3.0, 1.0}, 200);
  for (auto& p : pts) p += Vector2d(rng.normal(0.0, mm(5.0)), rng.normal(0.0, mm(5.0)));
  OrientationOptions branch, y_on_x;
  y_on_x.near_vertical_within = 0.0;  // disables eq. 6.7–6.11
  const SegmentOrientation good = segment_orientation(pts, wall, branch);
  const SegmentOrientation bad = segment_orientation(pts, wall, y_on_x);
  EXPECT_TRUE(good.near_vertical);
  EXPECT_FALSE(bad.near_vertical);
  EXPECT_NEAR(good.delta, deg(-0.5), deg(0.05));
  EXPECT_GT(std::abs(bad.delta - deg(-0.5)), deg(0.1));
}

TEST(SegmentOrientation, VarianceIsResidualSigmaSquaredOverAlongLineSpread) {
  // 3 points at t = −1, 0, 1 (Σt² = 2), noise-free: σ floored at 5 mm → var = 25e-6 / 2.
  const Segment wall{{-3.0, 2.0}, {3.0, 2.0}};
  const std::vector<Vector2d> pts{{-1.0, 2.0}, {0.0, 2.0}, {1.0, 2.0}};
  EXPECT_NEAR(segment_orientation(pts, wall, {}).variance, 25e-6 / 2.0, 1e-15);
  // Residuals +1, −2, +1 cm (mean 0 on the fitted line): σ² = 6e-4 / (3 − 2).
  const std::vector<Vector2d> noisy{{-1.0, 2.01}, {0.0, 1.98}, {1.0, 2.01}};
  EXPECT_NEAR(segment_orientation(noisy, wall, {}).variance, 6e-4 / 2.0, 1e-12);
}

TEST(SegmentOrientation, RejectsTooFewOrCoincidentPoints) {
  const Segment wall{{0.0, 0.0}, {1.0, 0.0}};
  const std::vector<Vector2d> one{{0.5, 0.0}};
  const std::vector<Vector2d> same{{0.5, 0.0}, {0.5, 0.0}, {0.5, 0.0}};
  EXPECT_THROW(segment_orientation(one, wall, {}), UsageError);
  EXPECT_THROW(segment_orientation(same, wall, {}), UsageError);
}

TEST(ThesisWeight, SymmetricViewGivesLengthOverDistance) {
  // o at the origin, segment y = 1 from x = −1 to 1: ∠op1p2 = ∠op2p1 = 45°, w = 2/1.
  EXPECT_NEAR(thesis_weight({0, 0}, {-1, 1}, {1, 1}), 2.0, 1e-12);
  // Same length at twice the distance: half the weight.
  EXPECT_NEAR(thesis_weight({0, 0}, {-1, 2}, {1, 2}), 1.0, 1e-12);
}

TEST(ThesisWeight, MatchesTheClosedFormAndTurnsNegativeForObliqueViews) {
  // cos(∠op1p2 − ∠op2p1) = (d² − ab)/(|op1||op2|), a, b = signed positions of p1, p2 from h.
  Rng rng(3);
  for (int k = 0; k < 200; ++k) {
    const double d = rng.uniform(0.1, 5.0), a = rng.uniform(-5.0, 5.0), b = rng.uniform(-5.0, 5.0);
    if (std::abs(b - a) < 1e-3) continue;
    const double closed = std::abs(b - a) / d * (d * d - a * b) / (std::hypot(d, a) * std::hypot(d, b));
    EXPECT_NEAR(thesis_weight({0, 0}, {a, d}, {b, d}), closed, 1e-9 * (1 + std::abs(closed)));
  }
  // Segment entirely to one side of h with ab > d²: a = 1, b = 3, d = 1 → w = 2·(1 − 3)/(√2√10).
  EXPECT_NEAR(thesis_weight({0, 0}, {1, 1}, {3, 1}), 2.0 * -2.0 / std::sqrt(20.0), 1e-12);
  // ab = d² is the boundary (cos = 0).
  EXPECT_NEAR(thesis_weight({0, 0}, {1, 1}, {1 + 1e-9, 1}), 0.0, 1e-6);
}

TEST(ThesisWeight, DegeneratesAsTheRobotApproachesTheSegmentsLine) {
  // |oh| → 0 with o beyond the segment's end: w → −∞ (returned as is until |oh| < 1 µm → 0).
  EXPECT_LT(thesis_weight({0, 0}, {1, 1e-3}, {2, 1e-3}), -900.0);
  EXPECT_EQ(thesis_weight({0, 0}, {1, 1e-7}, {2, 1e-7}), 0.0);
  // o on the segment's own line inside it: w → +∞; returned as 0 (no laser sees that).
  EXPECT_EQ(thesis_weight({0, 0}, {-1, 0}, {1, 0}), 0.0);
  EXPECT_EQ(thesis_weight({0, 0}, {1, 1}, {1, 1}), 0.0);
}

TEST(ThesisWeight, AtTheThesisPoseTheObliquelySeenWallsGetNegativeRawWeights) {
  // Room of §5.4 from (2.0, 1.0, 46°): the bottom wall (seen from x = 3.0 to 5.0 at 1 m) has
  // a·b ≈ 1·3 > d² = 1, so eq. 6.18 gives it a negative weight; it is clamped to 0.
  const LineMap room = sim::room_world();
  const Pose2 truth{2.0, 1.0, deg(46.0)};
  const auto scan = test::ray_cast_scan(room, truth);
  const auto matches = test::matches_by_true_hit(scan, truth);
  const OrientationCorrection c = correct_orientation(matches, room, truth, Pose2::identity());
  ASSERT_TRUE(c.fixed);
  int negative = 0;
  for (const auto& s : c.segments) {
    if (s.map_segment == 0) {
      EXPECT_LT(s.thesis_weight, 0.0);
    }
    if (s.thesis_weight < 0.0) {
      ++negative;
      EXPECT_EQ(s.weight, 0.0);
    }
  }
  EXPECT_GE(negative, 1);
  EXPECT_NEAR(c.delta, 0.0, 1e-9);  // seen from the truth: nothing to correct
}

TEST(CorrectOrientation, WeightedCombinationIsTheNormalisedWeightedMean) {
  // Hand-made: o at the origin, estimate = identity. Segment A (y = 1, x ∈ [−1, 1], w = 2/1)
  // with its points rotated +2° about o → Δθ_A = −2°; segment B (x = 2, y ∈ [−1, 1],
  // w = 2/2) rotated +4° → Δθ_B = −4°. Rotation about o keeps both weights.
  LineMap map;
  map.segments = {{{-1, 1}, {1, 1}}, {{2, -1}, {2, 1}}};
  const Pose2 est = Pose2::identity();
  const auto a = test::robot_points_on(Pose2{0, 0, deg(-2.0)}, {-1, 1}, {1, 1}, 11);
  const auto b = test::robot_points_on(Pose2{0, 0, deg(-4.0)}, {2, -1}, {2, 1}, 11);
  const std::vector<laser::SegmentMatch> matches{test::hand_match(0, a, est), test::hand_match(1, b, est)};
  const OrientationCorrection c = correct_orientation(matches, map, est, Pose2::identity());
  ASSERT_TRUE(c.fixed);
  ASSERT_EQ(c.segments.size(), 2u);
  EXPECT_NEAR(c.segments[0].thesis_weight, 2.0, 1e-9);
  EXPECT_NEAR(c.segments[1].thesis_weight, 1.0, 1e-9);
  EXPECT_NEAR(c.segments[0].weight, 2.0 / 3.0, 1e-9);
  EXPECT_NEAR(c.segments[1].weight, 1.0 / 3.0, 1e-9);
  EXPECT_FALSE(c.segments[0].near_vertical);
  EXPECT_TRUE(c.segments[1].near_vertical);
  EXPECT_NEAR(c.delta, deg(-8.0 / 3.0), 1e-9);  // (2·(−2°) + 1·(−4°)) / 3
  // var = Σ w_i² var_i.
  EXPECT_NEAR(c.variance, 4.0 / 9.0 * c.segments[0].variance + 1.0 / 9.0 * c.segments[1].variance, 1e-15);

  OrientationOptions equal;
  equal.weighting = OrientationWeighting::kEqual;  // eq. 6.12
  EXPECT_NEAR(correct_orientation(matches, map, est, Pose2::identity(), equal).delta, deg(-3.0), 1e-9);
  OrientationOptions inverse;
  inverse.weighting = OrientationWeighting::kInverseVariance;
  const OrientationCorrection iv = correct_orientation(matches, map, est, Pose2::identity(), inverse);
  const double wa = 1.0 / iv.segments[0].variance, wb = 1.0 / iv.segments[1].variance;
  EXPECT_NEAR(iv.delta, (wa * deg(-2.0) + wb * deg(-4.0)) / (wa + wb), 1e-9);
}

TEST(CorrectOrientation, AllObliqueSegmentsFallBackToEqualWeights) {
  // Both segments lie to one side of the foot of the perpendicular with ab > d²: w < 0.
  LineMap map;
  map.segments = {{{0, 1}, {5, 1}}, {{1, -0.5}, {5, -0.5}}};
  const Pose2 est = Pose2::identity();
  const auto a = test::robot_points_on(Pose2{0, 0, deg(-1.0)}, {2, 1}, {4, 1}, 11);
  const auto b = test::robot_points_on(Pose2{0, 0, deg(-1.0)}, {2, -0.5}, {4, -0.5}, 11);
  const std::vector<laser::SegmentMatch> matches{test::hand_match(0, a, est), test::hand_match(1, b, est)};
  const OrientationCorrection c = correct_orientation(matches, map, est, Pose2::identity());
  ASSERT_TRUE(c.fixed);
  EXPECT_TRUE(c.equal_weight_fallback);
  EXPECT_LT(c.segments[0].thesis_weight, 0.0);
  EXPECT_LT(c.segments[1].thesis_weight, 0.0);
  EXPECT_NEAR(c.delta, deg(-1.0), 1e-9);
}

TEST(CorrectOrientation, SkipsShortMatchesAndRejectsUnknownSegments) {
  LineMap map;
  map.segments = {{{-1, 1}, {1, 1}}};
  const Pose2 est = Pose2::identity();
  const std::vector<laser::SegmentMatch> short_match{
      test::hand_match(0, {{-1, 1}, {1, 1}}, est)};  // 2 points < min_points 3
  EXPECT_FALSE(correct_orientation(short_match, map, est, Pose2::identity()).fixed);
  const std::vector<laser::SegmentMatch> bad{test::hand_match(4, {{-1, 1}, {0, 1}, {1, 1}}, est)};
  EXPECT_THROW(correct_orientation(bad, map, est, Pose2::identity()), UsageError);
}

TEST(OrientationOptions, JsonRoundTripAndStrictKeys) {
  OrientationOptions o;
  o.weighting = OrientationWeighting::kInverseVariance;
  o.min_points = 7;
  const nlohmann::json j = o;
  const OrientationOptions back = j.get<OrientationOptions>();
  EXPECT_EQ(back.weighting, OrientationWeighting::kInverseVariance);
  EXPECT_EQ(back.min_points, 7);
  EXPECT_THROW((nlohmann::json{{"weigting", "equal"}}.get<OrientationOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"weighting", "median"}}.get<OrientationOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"min_point_sigma", 0.0}}.get<OrientationOptions>()), UsageError);
}

}  // namespace
}  // namespace locbench::pose_correction
