#include "algorithms/laser/eap_region.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/rng.h"

namespace locbench::laser {
namespace {

// P1 = (0, 0), P2 = (2, 0), d_limit = 0.2 m: the band is |y| ≤ 0.2, d3 = √4.04 = 2.00998 m.
const Segment kWall{{0.0, 0.0}, {2.0, 0.0}};
constexpr double kD = 0.2;

bool in_thesis(const EapRegion& r, double x, double y) { return r.contains({x, y}, RegionRule::kThesis); }
bool in_stadium(const EapRegion& r, double x, double y) { return r.contains({x, y}, RegionRule::kStadium); }

TEST(EapRegion, PointsInTheBandBetweenTheEndsAreMembers) {
  const EapRegion r(kWall, kD);
  for (const auto rule : {RegionRule::kThesis, RegionRule::kStadium}) {
    EXPECT_TRUE(r.contains({1.0, 0.0}, rule));
    EXPECT_TRUE(r.contains({1.0, 0.19}, rule));
    EXPECT_TRUE(r.contains({0.0, -0.19}, rule));
    EXPECT_TRUE(r.contains({2.0, 0.19}, rule));
    EXPECT_FALSE(r.contains({1.0, 0.21}, rule));  // outside ω2 (5.5)
    EXPECT_FALSE(r.contains({1.0, -0.25}, rule));
  }
}

TEST(EapRegion, BeyondEachEndCapOnlyTheDiscOfRadiusDLimitIsKept) {
  const EapRegion r(kWall, kD);
  // Along the axis: d2 = 0.15 ≤ d_limit keeps the point (min(d1, d2) ≤ d_limit, not ω3).
  EXPECT_TRUE(in_thesis(r, 2.15, 0.0));
  EXPECT_TRUE(in_thesis(r, -0.15, 0.0));
  // d2 = 0.21: d1 = 2.21 > d3 and d2 > d_limit → ω3 (5.17), removed.
  EXPECT_FALSE(in_thesis(r, 2.21, 0.0));
  EXPECT_FALSE(in_thesis(r, -0.21, 0.0));
  // Inside the band, off the axis, inside the disc: d2 = √(0.05² + 0.19²) = 0.1965.
  EXPECT_TRUE(in_thesis(r, 2.05, 0.19));
  EXPECT_TRUE(in_thesis(r, -0.05, -0.19));
}

TEST(EapRegion, TheBandCornersBeyondTheEndsAreOmega3UnderBothRules) {
  // The corners of the band just outside the end discs — where a reading of the figure might
  // expect ω1 and the stadium to differ. They do not: the thesis's rule removes them too.
  const EapRegion r(kWall, kD);
  struct P {
    double x, y;
  };
  // (2.10, 0.19): d2 = 0.2147 > 0.2, d1 = 2.1086 > d3 = 2.00998 → ω3.
  // (2.02, 0.199): d2 = √0.040001 = 0.2000025 > 0.2, d1 = 2.0298 > d3 → ω3.
  // (2.001, 0.1999): d2 = 0.19993 ≤ 0.2 → kept (a hair inside the disc).
  // (-0.06, 0.195): d1 = 0.2040 > 0.2, d2 = 2.0694 > d3 → ω3.
  for (const P p : {P{2.10, 0.19}, P{2.02, 0.199}, P{-0.06, 0.195}}) {
    EXPECT_FALSE(in_thesis(r, p.x, p.y)) << p.x << ", " << p.y;
    EXPECT_FALSE(in_stadium(r, p.x, p.y)) << p.x << ", " << p.y;
  }
  EXPECT_TRUE(in_thesis(r, 2.001, 0.1999));
  EXPECT_TRUE(in_stadium(r, 2.001, 0.1999));
}

TEST(EapRegion, ShortSegmentShorterThanDLimitIsAStadiumToo) {
  // L = 0.1 < d_limit: d3 = √(0.04 + 0.01) = 0.2236.
  const EapRegion r({{0.0, 0.0}, {0.1, 0.0}}, kD);
  EXPECT_TRUE(in_thesis(r, 0.25, 0.1));     // d2 = √(0.0225 + 0.01) = 0.180
  EXPECT_FALSE(in_thesis(r, -0.15, 0.15));  // d1 = 0.2121, d2 = 0.2915 > d3
  EXPECT_FALSE(in_stadium(r, -0.15, 0.15));
  EXPECT_TRUE(in_thesis(r, 0.05, -0.2));  // on the band's edge, between the ends
}

TEST(EapRegion, ThesisRuleEqualsStadiumOnRandomPointsNearRandomSegments) {
  // The proof is in eap_region.cpp; here 100 000 random points around segments from 1 cm to
  // 5 m long with d_limit from 5 cm to 1 m, concentrated on the end caps.
  Rng rng(20261122);
  int differ = 0, inside = 0;
  for (int s = 0; s < 200; ++s) {
    const Eigen::Vector2d p1(rng.uniform(-5, 5), rng.uniform(-5, 5));
    const double a = rng.uniform(-3.2, 3.2);
    const double len = std::exp(rng.uniform(std::log(0.01), std::log(5.0)));
    const double d = rng.uniform(0.05, 1.0);
    const Eigen::Vector2d u(std::cos(a), std::sin(a)), n(-u.y(), u.x());
    const EapRegion r({p1, p1 + len * u}, d);
    for (int k = 0; k < 500; ++k) {
      const double t = rng.uniform(-1.5 * d, len + 1.5 * d), h = rng.uniform(-1.5 * d, 1.5 * d);
      const Eigen::Vector2d p = p1 + t * u + h * n;
      const bool thesis = r.contains(p, RegionRule::kThesis);
      differ += thesis != r.contains(p, RegionRule::kStadium);
      inside += thesis;
      // And both agree with the core's distance to the closed segment.
      const double dist = distance_to_segment({p1, p1 + len * u}, p);
      if (std::abs(dist - d) > 1e-9) {
        EXPECT_EQ(thesis, dist <= d);
      }
    }
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(inside, 25000);  // the sample really straddles the boundary
  EXPECT_LT(inside, 75000);
}

TEST(EapRegion, DistanceToSegmentIsTheCoreDistance) {
  const EapRegion r(kWall, kD);
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(1, 0.1), Eigen::Vector2d(-1, 1), Eigen::Vector2d(3, -1), Eigen::Vector2d(2, 0)}) {
    EXPECT_NEAR(r.distance_to_segment(p), distance_to_segment(kWall, p), 1e-15);
  }
}

TEST(EapRegion, RejectsZeroLengthSegmentsAndNonPositiveDLimit) {
  EXPECT_THROW(EapRegion({{1, 1}, {1, 1}}, kD), UsageError);
  EXPECT_THROW(EapRegion(kWall, 0.0), UsageError);
  EXPECT_THROW(EapRegion(kWall, std::nan("")), UsageError);
  EXPECT_EQ(region_rule_from_string("stadium"), RegionRule::kStadium);
  EXPECT_THROW(region_rule_from_string("disc"), UsageError);
}

TEST(EapRegion, NonFinitePointIsNeverAMember) {
  const EapRegion r(kWall, kD);
  EXPECT_FALSE(r.contains({std::nan(""), 0.0}, RegionRule::kThesis));
  EXPECT_FALSE(r.contains({1.0, std::nan("")}, RegionRule::kStadium));
}

}  // namespace
}  // namespace locbench::laser
