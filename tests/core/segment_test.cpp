#include "core/segment.h"

#include <gtest/gtest.h>

#include "core/units.h"

namespace locbench {
namespace {

TEST(SegmentLine, NormalFormOfAVerticalWallAtXEquals8) {
  const Segment s{{8.0, 0.0}, {8.0, 8.0}};
  const LineParams l = s.line();
  EXPECT_NEAR(l.rho, 8.0, 1e-12);
  EXPECT_NEAR(l.beta, 0.0, 1e-12);
}

TEST(SegmentLine, RhoIsNonNegativeWhicheverWayTheSegmentRuns) {
  const Segment s{{0.0, -2.0}, {4.0, -2.0}};  // y = −2
  const LineParams l = s.line();
  EXPECT_NEAR(l.rho, 2.0, 1e-12);
  EXPECT_NEAR(l.beta, deg(-90), 1e-12);
  const Segment r{s.p2, s.p1};
  EXPECT_NEAR(r.line().rho, 2.0, 1e-12);
  EXPECT_NEAR(r.line().beta, deg(-90), 1e-12);
}

TEST(SegmentLine, EndPointsSatisfyEquation5_1) {
  const Segment s{{1.0, 3.0}, {4.0, -1.0}};
  const LineParams l = s.line();
  EXPECT_NEAR(signed_distance_to_line(l, s.p1), 0.0, 1e-12);
  EXPECT_NEAR(signed_distance_to_line(l, s.p2), 0.0, 1e-12);
}

TEST(SegmentDistance, IsPerpendicularInsideAndToTheEndBeyondIt) {
  const Segment s{{0.0, 0.0}, {2.0, 0.0}};
  EXPECT_NEAR(distance_to_segment(s, {1.0, 0.5}), 0.5, 1e-12);
  EXPECT_NEAR(distance_to_segment(s, {3.0, 0.0}), 1.0, 1e-12);
  EXPECT_NEAR(distance_to_segment(s, {-3.0, 4.0}), 5.0, 1e-12);
}

}  // namespace
}  // namespace locbench
