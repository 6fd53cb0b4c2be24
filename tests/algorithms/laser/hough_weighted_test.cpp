#include "algorithms/laser/hough_weighted.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/units.h"

namespace locbench::laser {
namespace {

// A sensor at the world origin looking along +x (heading 0) and the wall y = 2 (ρ = 2, β = 90°).
ScanPoint at(double x, double y) {
  ScanPoint p;
  p.world = p.robot = {x, y};
  p.range = std::hypot(x, y);
  p.bearing = std::atan2(y, x);
  return p;
}
const LineParams kWall{2.0, deg(90.0)};

// Three points within 0.2 m of the wall, two outside.
std::vector<ScanPoint> wall_points() {
  return {at(0.0, 2.0), at(1.5, 2.1), at(-1.0, 1.85), at(2.0, 2.25), at(3.0, 1.5)};
}

TEST(HoughWeighted, RectangularWindowIsOneUpToDLimitInclusive) {
  EXPECT_EQ(rectangular_window(0.25, 0.25), 1.0);
  EXPECT_EQ(rectangular_window(-0.25, 0.25), 1.0);
  EXPECT_EQ(rectangular_window(0.2500001, 0.25), 0.0);
  EXPECT_EQ(rectangular_window(std::nan(""), 0.25), 0.0);
}

TEST(HoughWeighted, CountScoreIsTheNumberOfPointsWithinDLimitOfTheLine) {
  HoughOptions o;  // g ≡ 1 (5.11)
  EXPECT_DOUBLE_EQ(hough_score(wall_points(), 0.0, kWall, o), 3.0);
  o.d_limit = 0.3;  // now (2, 2.25) is inside too; (3, 1.5) still 0.5 m off
  EXPECT_DOUBLE_EQ(hough_score(wall_points(), 0.0, kWall, o), 4.0);
}

TEST(HoughWeighted, RangeScoreSumsRangeOverRhoMin) {
  HoughOptions o;
  o.g.kind = HoughWeighting::kRange;  // (5.10)
  o.g.rho_min = 0.5;
  // ranges 2, √(2.25 + 4.41) = 2.5807, √(1 + 3.4225) = 2.1030
  const double expected = (2.0 + std::sqrt(6.66) + std::sqrt(4.4225)) / 0.5;
  EXPECT_NEAR(hough_score(wall_points(), 0.0, kWall, o), expected, 1e-12);
  EXPECT_NEAR(expected, 13.3674, 1e-4);
}

TEST(HoughWeighted, RangeIncidenceScoreDividesByTheCosineOfTheIncidenceAngle) {
  HoughOptions o;
  o.g.kind = HoughWeighting::kRangeIncidence;  // (5.8–5.9)
  o.g.rho_min = 0.5;
  // For a point (x, y) seen from the origin, cos(α + θ − β) = cos(α − 90°) = sin α = y/r, so
  // g = (r/ρ_min)·(r/y) = r²/(ρ_min·y): 4/1, 6.66/1.05, 4.4225/0.925.
  const double expected = 4.0 / 1.0 + 6.66 / 1.05 + 4.4225 / 0.925;
  EXPECT_NEAR(hough_score(wall_points(), 0.0, kWall, o), expected, 1e-12);
  // The same points seen by a sensor turned by 30° (bearings 30° smaller) weigh the same.
  std::vector<ScanPoint> turned = wall_points();
  for (auto& p : turned) p.bearing -= deg(30.0);
  EXPECT_NEAR(hough_score(turned, deg(30.0), kWall, o), expected, 1e-12);
}

TEST(HoughWeighted, GrazingIncidenceIsFlooredInsteadOfInfinite) {
  HoughWeight g;
  g.kind = HoughWeighting::kRangeIncidence;
  g.rho_min = 0.5;
  g.min_cos_incidence = 0.05;
  // (100, 2): cos = 2/100.02 = 0.019996 < 0.05 → g = 100.02/0.5/0.05 = 4000.8.
  const ScanPoint far = at(100.0, 2.0);
  EXPECT_NEAR(hough_weight(far, 0.0, kWall.beta, g), far.range / 0.5 / 0.05, 1e-9);
  // A beam exactly along the wall's normal from the other side (normal pointing at the sensor)
  // weighs as much as from the front: |cos|.
  EXPECT_NEAR(hough_weight(at(0.0, 2.0), 0.0, deg(-90.0), g), 4.0, 1e-12);
}

TEST(HoughWeighted, RejectsBadOptionsAndNames) {
  HoughOptions o;
  o.d_limit = 0.0;
  EXPECT_THROW(hough_score(wall_points(), 0.0, kWall, o), UsageError);
  o = {};
  o.g.rho_min = -1.0;
  EXPECT_THROW(hough_score(wall_points(), 0.0, kWall, o), UsageError);
  EXPECT_EQ(hough_weighting_from_string("range_incidence"), HoughWeighting::kRangeIncidence);
  EXPECT_THROW(hough_weighting_from_string("rwht"), UsageError);
}

}  // namespace
}  // namespace locbench::laser
