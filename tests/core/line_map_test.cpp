#include "core/line_map.h"

#include <gtest/gtest.h>

#include "core/units.h"

namespace locbench {
namespace {

LineMap unit_box(double side) {
  return {"box", {{{0, 0}, {side, 0}}, {{side, 0}, {side, side}}, {{side, side}, {0, side}}, {{0, side}, {0, 0}}}};
}

TEST(RayCast, HitsTheNearestWallAtTheAnalyticRange) {
  const LineMap m = unit_box(8.0);
  const auto hit = m.ray_cast({2.0, 1.0}, 0.0, 20.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range, 6.0, 1e-12);
  EXPECT_EQ(hit->segment, 1u);
}

TEST(RayCast, ObliqueRangeFollowsTheCosineOfTheIncidence) {
  const LineMap m = unit_box(8.0);
  const auto hit = m.ray_cast({2.0, 1.0}, deg(-60), 20.0);  // hits y = 0
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range, 1.0 / std::sin(deg(60)), 1e-12);
  EXPECT_EQ(hit->segment, 0u);
}

TEST(RayCast, ReturnsNothingBeyondMaxRange) {
  const LineMap m = unit_box(8.0);
  EXPECT_FALSE(m.ray_cast({2.0, 1.0}, 0.0, 5.9));
}

TEST(RayCast, MissesASegmentPastItsEnd) {
  const LineMap m{"one", {{{1.0, -1.0}, {1.0, 1.0}}}};
  EXPECT_TRUE(m.ray_cast({0, 0}, deg(40), 10.0));
  EXPECT_FALSE(m.ray_cast({0, 0}, deg(50), 10.0));
}

}  // namespace
}  // namespace locbench
