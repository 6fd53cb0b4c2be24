#include "algorithms/laser/line_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "algorithms/laser/scan_points.h"
#include "core/scan.h"

namespace locbench::laser {
namespace {

TEST(LineFit, HorizontalWallAtTwoMetresHasRhoTwoAndNormalUp) {
  const std::vector<Eigen::Vector2d> pts{{0, 2}, {1, 2}, {2, 2}, {3, 2}};
  const LineFit f = fit_line(pts);
  EXPECT_NEAR(f.line.rho, 2.0, 1e-12);
  EXPECT_NEAR(f.line.beta, std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(f.rms, 0.0, 1e-12);
  EXPECT_NEAR((f.first - Eigen::Vector2d(0, 2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((f.last - Eigen::Vector2d(3, 2)).norm(), 0.0, 1e-12);
}

TEST(LineFit, VerticalWallLeftOfOriginHasNormalPointingAwayFromOrigin) {
  const std::vector<Eigen::Vector2d> pts{{-1.5, -1}, {-1.5, 0}, {-1.5, 1}};
  const LineFit f = fit_line(pts);
  EXPECT_NEAR(f.line.rho, 1.5, 1e-12);
  EXPECT_NEAR(std::abs(f.line.beta), std::numbers::pi, 1e-12);
}

TEST(LineFit, ObliqueLineMinimisesPerpendicularNotVerticalResiduals) {
  // Points on y = x + 1, each in a pair 0.01 m either side of it: the line is recovered (an
  // ordinary y-on-x regression would be too, but only the orthogonal fit gives rms = 0.01).
  std::vector<Eigen::Vector2d> pts;
  const Eigen::Vector2d n(-std::sqrt(0.5), std::sqrt(0.5));
  for (int i = 0; i < 10; ++i) {
    const double s = i * 0.3;
    pts.push_back(Eigen::Vector2d(s, s + 1) + 0.01 * n);
    pts.push_back(Eigen::Vector2d(s, s + 1) - 0.01 * n);
  }
  const LineFit f = fit_line(pts);
  EXPECT_NEAR(f.line.rho, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(f.line.beta, 3 * std::numbers::pi / 4, 1e-9);
  EXPECT_NEAR(f.rms, 0.01, 1e-9);
}

TEST(ScanPoints, SkipsInvalidBeamsAndAppliesMountThenPose) {
  Scan s;
  s.bearings = {0.0, std::numbers::pi / 2};
  s.ranges = {1.0, 9.0};
  s.max_range = 8.0;
  s.sensor_pose = Pose2{0.1, 0.0, 0.0};
  const auto pts = scan_points(s, Pose2{1.0, 2.0, std::numbers::pi / 2});
  ASSERT_EQ(pts.size(), 1u);
  EXPECT_EQ(pts[0].beam, 0u);
  EXPECT_NEAR(pts[0].robot.x(), 1.1, 1e-12);
  EXPECT_NEAR(pts[0].world.x(), 1.0, 1e-12);
  EXPECT_NEAR(pts[0].world.y(), 3.1, 1e-12);
}

TEST(ScanPoints, EvenlySpacedBearingsGiveTheSamePointsAsDirectTrigonometry) {
  // The fast path rotates cos/sin from beam to beam; it must agree with std::cos/std::sin.
  Scan s;
  s.bearings = even_bearings(1441, -std::numbers::pi / 2, std::numbers::pi / 2);
  s.ranges.assign(s.bearings.size(), 7.5);
  s.max_range = 8.0;
  s.sensor_pose = Pose2{0.2, -0.1, 0.3};
  const Pose2 robot{3.0, 4.0, 2.0};
  const auto pts = scan_points(s, robot);
  ASSERT_EQ(pts.size(), 1441u);
  for (const ScanPoint& p : pts) {
    const Eigen::Vector2d want = robot * (s.sensor_pose * s.point(p.beam));
    EXPECT_NEAR((p.world - want).norm(), 0.0, 1e-12) << p.beam;
  }
}

}  // namespace
}  // namespace locbench::laser
