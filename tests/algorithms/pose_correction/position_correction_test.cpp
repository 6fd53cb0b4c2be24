#include "algorithms/pose_correction/position_correction.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"
#include "tests/algorithms/pose_correction/ray_cast_matches.h"

namespace locbench::pose_correction {
namespace {

using Eigen::Vector2d;

// The room of §5.4 rotated by `angle` about the origin, and a pose mapped with it.
LineMap rotated(const LineMap& m, double angle) {
  const Pose2 r{0.0, 0.0, angle};
  LineMap out = m;
  for (auto& s : out.segments) {
    s.p1 = r * s.p1;
    s.p2 = r * s.p2;
  }
  return out;
}

struct Case {
  const char* name;
  double room_rotation;
};

class BothSolvers : public ::testing::TestWithParam<Case> {};

TEST_P(BothSolvers, RecoverAKnownOffsetFromNoiseFreePoints) {
  // True pose (2.0, 1.0, 46°) in the room (or its image in the rotated room); the estimate has
  // the right heading and is off by (+0.1, +0.1) in the room's own frame, so Δ = −(R·0.1, R·0.1).
  const double rot = GetParam().room_rotation;
  const LineMap room = rotated(sim::room_world(), rot);
  const Pose2 r{0.0, 0.0, rot};
  const Pose2 truth = r * Pose2{2.0, 1.0, deg(46.0)};
  const Vector2d offset = r * Vector2d(0.1, 0.1) - r.translation();
  const Pose2 estimate{truth.x + offset.x(), truth.y + offset.y(), truth.theta};
  const auto matches = test::matches_by_true_hit(test::ray_cast_scan(room, truth), estimate);
  ASSERT_GE(matches.size(), 5u);
  for (const auto method : {PositionMethod::kPointToLine, PositionMethod::kPointToPoint}) {
    PositionOptions o;
    o.method = method;
    const PositionCorrection c = correct_position(matches, room, estimate, Pose2::identity(), o);
    ASSERT_TRUE(c.fixed);
    EXPECT_NEAR(c.delta.x(), -offset.x(), 1e-9);
    EXPECT_NEAR(c.delta.y(), -offset.y(), 1e-9);
    EXPECT_NEAR(c.residual_sigma, 0.0, 1e-7);  // √(rounding)
    // Noise-free: the covariance is the floor σ² A⁻¹.
    const PositionNormalEquations eq = position_normal_equations(matches, room, estimate, Pose2::identity(), o);
    EXPECT_TRUE(c.covariance.isApprox(o.min_point_sigma * o.min_point_sigma * eq.matrix().inverse(), 1e-9));
  }
}

INSTANTIATE_TEST_SUITE_P(Rooms, BothSolvers, ::testing::Values(Case{"axis_aligned", 0.0}, Case{"oblique", deg(30.0)}),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(ThesisClosedForm, DeltaXIsRightButDeltaYDividesByK4WhichVanishesInAnAxisAlignedRoom) {
  // Eq. 6.27: Δx = (k1k5 − k2k4)/(k4² − k3k5), Δy = (−k1 − k3Δx)/k4.
  for (const double rot : {0.0, deg(30.0)}) {
    const LineMap room = rotated(sim::room_world(), rot);
    const Pose2 r{0.0, 0.0, rot};
    const Pose2 truth = r * Pose2{2.0, 1.0, deg(46.0)};
    const Pose2 estimate{truth.x + 0.1, truth.y - 0.05, truth.theta};
    const auto matches = test::matches_by_true_hit(test::ray_cast_scan(room, truth), estimate);
    PositionOptions o;
    o.method = PositionMethod::kPointToLine;
    const PositionNormalEquations k = position_normal_equations(matches, room, estimate, Pose2::identity(), o);
    const Vector2d direct = k.matrix().fullPivLu().solve(k.rhs());
    const double dx = (k.k1 * k.k5 - k.k2 * k.k4) / (k.k4 * k.k4 - k.k3 * k.k5);
    const double dy = (-k.k1 - k.k3 * dx) / k.k4;
    EXPECT_NEAR(direct.x(), -0.1, 1e-9);
    EXPECT_NEAR(direct.y(), 0.05, 1e-9);
    EXPECT_NEAR(dx, -0.1, 1e-9);  // the published Δx is right
    if (rot == 0.0) {
      // k4 = Σ cos β sin β is rounding noise (cos(π/2) = 6e-17 per point): Δy is garbage.
      EXPECT_LT(std::abs(k.k4), 1e-12 * k.k3);
      EXPECT_FALSE(std::isfinite(dy) && std::abs(dy - 0.05) < 1e-3) << "dy = " << dy;
    } else {
      EXPECT_NEAR(dy, 0.05, 1e-9);  // fine when k4 ≠ 0
    }
    // Ours (Cramer) in both rooms.
    EXPECT_NEAR(correct_position(matches, room, estimate, Pose2::identity(), o).delta.y(), 0.05, 1e-9);
  }
}

TEST(PointToPoint, WeightsAreInverseSquaredCosinesOfTheIncidenceCappedForGrazingBeams) {
  // Wall y = 2 (β = 90°, ρ = 2) seen from the origin. A point at (2, 2): beam at 45° to the
  // normal, w = 1/cos²45° = 2. A point at (20, 2): 84.3° > 75° → capped at 1/cos²75°.
  LineMap map;
  map.segments = {{{-30, 2}, {30, 2}}};
  const Pose2 est = Pose2::identity();
  PositionOptions o;
  o.min_points = 1;
  const std::vector<laser::SegmentMatch> near{test::hand_match(0, {{2, 2}}, est)};
  const std::vector<laser::SegmentMatch> grazing{test::hand_match(0, {{20, 2}}, est)};
  EXPECT_NEAR(position_normal_equations(near, map, est, Pose2::identity(), o).k5, 2.0, 1e-9);
  const double cap = 1.0 / std::pow(std::cos(deg(75.0)), 2);
  EXPECT_NEAR(position_normal_equations(grazing, map, est, Pose2::identity(), o).k5, cap, 1e-9);
  o.method = PositionMethod::kPointToLine;
  EXPECT_NEAR(position_normal_equations(grazing, map, est, Pose2::identity(), o).k5, 1.0, 1e-12);
}

TEST(PointToPoint, IncidenceUsesTheSensorMountHeading) {
  // Sensor turned by 90° on the robot: a point straight ahead of the sensor (bearing 0) on a
  // wall in front of it is a head-on beam (w = 1) even though it lies at 90° in the robot frame.
  LineMap map;
  map.segments = {{{-5, 2}, {5, 2}}};
  const Pose2 est = Pose2::identity();
  const Pose2 mount{0.0, 0.0, deg(90.0)};
  laser::SegmentMatch m = test::hand_match(0, {{0, 2}}, est);
  m.points[0].bearing = 0.0;
  PositionOptions o;
  o.min_points = 1;
  const std::vector<laser::SegmentMatch> ms{m};
  EXPECT_NEAR(position_normal_equations(ms, map, est, mount, o).k5, 1.0, 1e-12);
}

TEST(Degenerate, TwoParallelCorridorWallsDoNotDeterminePosition) {
  const LineMap corridor = sim::corridor_world(12.0);  // walls 0: y = −0.9, 2: y = +0.9
  const Pose2 truth{3.0, 0.1, deg(2.0)};
  const Pose2 estimate{3.2, 0.0, deg(2.0)};
  auto matches = test::matches_by_true_hit(test::ray_cast_scan(corridor, truth), estimate);
  ASSERT_EQ(matches.size(), 2u);  // the end wall at x = 12 is beyond 8 m
  const PositionCorrection c = correct_position(matches, corridor, estimate, Pose2::identity());
  EXPECT_FALSE(c.fixed);
  EXPECT_EQ(c.segments_used, 2u);
  EXPECT_NEAR(c.angle_spread, 0.0, 1e-12);
  EXPECT_EQ(c.delta, Vector2d::Zero());
  // The normal matrix is rank 1: k3 ≈ 0 (both normals along y).
  const PositionNormalEquations eq = position_normal_equations(matches, corridor, estimate, Pose2::identity(), {});
  EXPECT_LT(std::abs(eq.k3 * eq.k5 - eq.k4 * eq.k4), 1e-12 * eq.k5 * eq.k5);
}

TEST(Degenerate, AngleSpreadThresholdDecides) {
  // A second wall at 8° or 12° to the first: below / above the 10° default.
  for (const double tilt : {8.0, 12.0}) {
    LineMap map;
    map.segments = {{{-5, 2}, {5, 2}}, {{-5, -2}, {5, -2 + 10 * std::tan(deg(tilt))}}};
    const Pose2 truth = Pose2::identity();
    const auto matches = test::matches_by_true_hit(test::ray_cast_scan(map, truth), Pose2{0.05, -0.05, 0.0});
    ASSERT_EQ(matches.size(), 2u);
    const PositionCorrection c = correct_position(matches, map, Pose2{0.05, -0.05, 0.0}, Pose2::identity());
    EXPECT_NEAR(c.angle_spread, deg(tilt), 1e-9);
    EXPECT_EQ(c.fixed, tilt > 10.0) << tilt;
    if (c.fixed) {
      EXPECT_NEAR(c.delta.x(), -0.05, 1e-9);
      EXPECT_NEAR(c.delta.y(), 0.05, 1e-9);
    }
  }
}

TEST(CorrectPosition, RejectsInvalidOptionsAndUnknownSegments) {
  LineMap map;
  map.segments = {{{-5, 2}, {5, 2}}};
  const Pose2 est = Pose2::identity();
  const std::vector<laser::SegmentMatch> bad{test::hand_match(3, {{0, 2}, {1, 2}, {2, 2}}, est)};
  EXPECT_THROW(correct_position(bad, map, est, Pose2::identity()), UsageError);
  PositionOptions o;
  o.max_incidence = deg(90.0);
  EXPECT_THROW(correct_position({}, map, est, Pose2::identity(), o), UsageError);
  EXPECT_THROW((nlohmann::json{{"method", "point_to_plane"}}.get<PositionOptions>()), UsageError);
  const nlohmann::json j = PositionOptions{};
  EXPECT_EQ(j.at("method"), "point_to_point");
}

}  // namespace
}  // namespace locbench::pose_correction
