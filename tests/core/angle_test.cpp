#include "core/angle.h"

#include <gtest/gtest.h>

namespace locbench {
namespace {

TEST(WrapAngle, KeepsAnglesInsideMinusPiToPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.5), 0.5);
  EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-3 * kPi / 2), kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(kPi), -kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(7 * 2 * kPi + 0.25), 0.25, 1e-9);
}

TEST(AngleDiff, TakesTheShortWayAcrossPi) {
  EXPECT_NEAR(angle_diff(deg(179), deg(-179)), deg(-2), 1e-12);
  EXPECT_NEAR(angle_diff(deg(-179), deg(179)), deg(2), 1e-12);
}

TEST(Units, ConvertAtTheEdges) {
  EXPECT_DOUBLE_EQ(deg(180), kPi);
  EXPECT_DOUBLE_EQ(to_deg(kPi / 2), 90.0);
  EXPECT_DOUBLE_EQ(mm(12.64), 0.01264);
  EXPECT_DOUBLE_EQ(to_mm(0.2), 200.0);
}

}  // namespace
}  // namespace locbench
