// UMBmark (§2.1, Borenstein & Feng): a wrong wheelbase (E_b ≠ 1) gives the Type A error, unequal
// wheel diameters (E_d ≠ 1) the Type B error, and the return-error centroids of the clockwise and
// counter-clockwise runs separate as Borenstein describes. Return errors are expressed in the
// start frame (x along the first leg, y to its left), where Borenstein's eq. 2.3 and 2.6 hold:
// β = (x_cw − x_ccw)/(−4L), α = (x_cw + x_ccw)/(−4L).
#include <gtest/gtest.h>

#include <cmath>

#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

constexpr double kSide = 4.0;

// The noise-free ideal robot on a 4 m square, one run each way, with E_d and E_b applied to the
// true geometry (keeping the mean diameter, so E_o = 1).
UmbmarkSummary square(double e_d, double e_b, std::vector<UmbmarkRun>* runs = nullptr) {
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kUmbmark;
  s.motion.side = kSide;
  s.motion.runs = 1;
  const double d = s.robot.nominal.diameter_left;
  s.robot.actual.diameter_left = d * 2.0 / (e_d + 1.0);
  s.robot.actual.diameter_right = d * 2.0 * e_d / (e_d + 1.0);
  s.robot.actual.wheelbase = s.robot.nominal.wheelbase * e_b;
  const auto r = simulate(s, 1);
  if (runs) *runs = r.umbmark_runs;
  return summarize_umbmark(r.umbmark_runs);
}

TEST(Umbmark, CorrectGeometryReturnsToTheStartBothWays) {
  const auto s = square(1.0, 1.0);
  EXPECT_LT(s.e_max_syst, 1e-9);
}

TEST(Umbmark, WrongWheelbaseGivesTypeAMirrorImageErrors) {
  // E_b = 1.02: every 90° turn falls short by α = 90°(1 − 1/E_b) = 1.765° in both directions,
  // so the CW and CCW end points are mirror images about the first leg.
  const auto s = square(1.0, 1.02);
  EXPECT_NEAR(s.centroid_cw.x(), s.centroid_ccw.x(), 1e-9);
  EXPECT_NEAR(s.centroid_cw.y(), -s.centroid_ccw.y(), 1e-9);
  EXPECT_GT(s.e_max_syst, 0.2);
  const double alpha = (s.centroid_cw.x() + s.centroid_ccw.x()) / (-4.0 * kSide);
  const double beta = (s.centroid_cw.x() - s.centroid_ccw.x()) / (-4.0 * kSide);
  EXPECT_NEAR(alpha, deg(90.0) * (1.0 - 1.0 / 1.02), 0.1 * deg(1.765));
  EXPECT_NEAR(beta, 0.0, 1e-9);
  // Borenstein's E_b estimate (2.7) recovers the true E_b.
  EXPECT_NEAR(deg(90.0) / (deg(90.0) - alpha), 1.02, 0.002);
}

TEST(Umbmark, UnequalWheelsGiveTypeBCurvatureErrors) {
  // E_d = 1.002: every straight leg curves left by β ≈ L(E_d − 1)/B = 0.021 rad in both
  // directions. It adds to the CW turns and subtracts from the CCW turns, so the centroids
  // lie on opposite sides in x and on the same side in y (to first order in β: the mismatch
  // is ~10% here).
  const auto s = square(1.002, 1.0);
  const double b = preset("ideal").robot.nominal.wheelbase;
  EXPECT_LT(s.centroid_cw.x() * s.centroid_ccw.x(), 0.0);
  EXPECT_NEAR(s.centroid_cw.x(), -s.centroid_ccw.x(), 0.15 * std::abs(s.centroid_cw.x()));
  EXPECT_GT(s.centroid_cw.y() * s.centroid_ccw.y(), 0.0);
  EXPECT_NEAR(s.centroid_cw.y(), s.centroid_ccw.y(), 0.15 * std::abs(s.centroid_cw.y()));
  const double beta = (s.centroid_cw.x() - s.centroid_ccw.x()) / (-4.0 * kSide);
  const double alpha = (s.centroid_cw.x() + s.centroid_ccw.x()) / (-4.0 * kSide);
  const double true_beta = kSide * (0.002 / 1.001) / b;  // (U_R − U_L)/B over one leg
  EXPECT_NEAR(beta, true_beta, 0.03 * true_beta);
  EXPECT_LT(std::abs(alpha), 0.05 * true_beta);
  // Borenstein's E_d estimate (2.4–2.5) recovers the true E_d.
  const double radius = (kSide / 2.0) / std::sin(beta / 2.0);
  EXPECT_NEAR((radius + b / 2.0) / (radius - b / 2.0), 1.002, 0.0001);
}

TEST(Umbmark, ReturnErrorIsTrueEndMinusOdometryEndInTheStartFrame) {
  std::vector<UmbmarkRun> runs;
  square(1.002, 1.01, &runs);
  ASSERT_EQ(runs.size(), 2u);
  for (const auto& r : runs) {
    const Pose2 t = between(r.start, r.true_end);
    const Pose2 o = between(r.start, r.odometry_end);
    EXPECT_NEAR(r.error.x(), t.x - o.x, 1e-12);
    EXPECT_NEAR(r.error.y(), t.y - o.y, 1e-12);
    // The ideal robot's odometry believes it came back.
    EXPECT_LT(translation_distance(r.odometry_end, r.start), 1e-9);
    EXPECT_GT(r.t_end, r.t_start);
  }
  EXPECT_EQ(runs[0].direction, Direction::kClockwise);
  EXPECT_EQ(runs[1].direction, Direction::kCounterClockwise);
}

TEST(Umbmark, TrilobotPresetRunsFiveEachWayWithResetsBetweenRuns) {
  const auto r = simulate(preset("umbmark_trilobot"), 3);
  ASSERT_EQ(r.umbmark_runs.size(), 10u);
  for (int i = 0; i < 10; ++i) {
    const auto& run = r.umbmark_runs[static_cast<std::size_t>(i)];
    EXPECT_EQ(run.direction, i < 5 ? Direction::kClockwise : Direction::kCounterClockwise);
    EXPECT_EQ(run.run, i % 5);
    // Every run starts where the robot was put back.
    EXPECT_EQ(run.start.x, 0.0);
    EXPECT_EQ(run.start.y, 0.0);
  }
  // Turn slip and the coarse 12.7 mm ticks give a large systematic error (thesis: 650–773 mm).
  const auto s = summarize_umbmark(r.umbmark_runs);
  EXPECT_GT(s.e_max_syst, 0.3);
  EXPECT_LT(s.e_max_syst, 1.2);
}

}  // namespace
}  // namespace locbench::sim
