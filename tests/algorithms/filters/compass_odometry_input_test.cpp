#include "algorithms/filters/compass_odometry_input.h"

#include <gtest/gtest.h>

namespace locbench::filters {
namespace {

TEST(CompassOdometryInput, PairsEachSampleWithTheNearestUnusedCompassReading) {
  const NominalModel m{0.01, 0.02, 0.2};
  const std::vector<EncoderReading> enc{{0.0, 0, 0}, {0.25, 5, 4}, {0.5, 10, 8}, {0.75, 12, 9}, {1.0, 12, 9}};
  // 0.26 belongs to the sample at 0.25; nothing near 0.5; 0.70 and 0.78 both near 0.75: the
  // nearer one (0.78) is taken; 0.98 goes to 1.0.
  const std::vector<CompassReading> cmp{{0.01, 0.0}, {0.26, 0.1}, {0.70, 0.2}, {0.78, 0.3}, {0.98, 0.4}};
  const auto s = pair_encoder_compass(enc, cmp, m, 0.1);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(s[0].t, 0.25);
  EXPECT_EQ(s[0].encoder_index, 1u);
  EXPECT_DOUBLE_EQ(s[0].u.left, 0.05);
  EXPECT_DOUBLE_EQ(s[0].u.right, 0.08);
  ASSERT_TRUE(s[0].compass);
  EXPECT_DOUBLE_EQ(*s[0].compass, 0.1);
  EXPECT_FALSE(s[1].compass);
  ASSERT_TRUE(s[2].compass);
  EXPECT_DOUBLE_EQ(*s[2].compass, 0.3);
  ASSERT_TRUE(s[3].compass);
  EXPECT_DOUBLE_EQ(*s[3].compass, 0.4);
  EXPECT_DOUBLE_EQ(s[3].u.left, 0.0);
}

TEST(CompassOdometryInput, EdgeCases) {
  const NominalModel m{0.01, 0.01, 0.2};
  EXPECT_TRUE(pair_encoder_compass({}, {}, m, 0.1).empty());
  const std::vector<EncoderReading> one{{0.0, 0, 0}};
  EXPECT_TRUE(pair_encoder_compass(one, {}, m, 0.1).empty());
  const std::vector<EncoderReading> two{{0.0, 0, 0}, {0.1, -3, 3}};
  const auto s = pair_encoder_compass(two, {}, m, 0.1);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_DOUBLE_EQ(s[0].u.left, -0.03);
  EXPECT_FALSE(s[0].compass);
  EXPECT_THROW(pair_encoder_compass(two, {}, m, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::filters
