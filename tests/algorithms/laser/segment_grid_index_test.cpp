#include "algorithms/laser/segment_grid_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/rng.h"
#include "eap_test_helpers.h"

namespace locbench::laser {
namespace {

bool lists(const SegmentGridIndex& idx, const Eigen::Vector2d& p, std::uint32_t j) {
  const auto c = idx.candidates(p);
  return std::find(c.begin(), c.end(), j) != c.end();
}

TEST(SegmentBoxDistance, HandMadeCases) {
  const Eigen::Vector2d lo(0, 0), hi(1, 1);
  EXPECT_EQ(segment_box_distance({-1, 0.5}, {2, 0.5}, lo, hi), 0.0);         // crosses
  EXPECT_EQ(segment_box_distance({0.2, 0.2}, {0.3, 0.3}, lo, hi), 0.0);      // inside
  EXPECT_DOUBLE_EQ(segment_box_distance({-1, 1.5}, {2, 1.5}, lo, hi), 0.5);  // above
  // A diagonal passing the corner (1, 1) at distance √2/2 · 0.5.
  EXPECT_NEAR(segment_box_distance({1.5, 1.0}, {1.0, 1.5}, lo, hi), std::sqrt(0.125), 1e-15);
  EXPECT_DOUBLE_EQ(segment_box_distance({3, 4}, {3, 5}, lo, hi), std::hypot(2.0, 3.0));
}

TEST(SegmentGridIndex, RoomCellsListTheWallsNearThemAndNothingFarAway) {
  const SegmentGridIndex idx(sim::room_world());
  // Automatic: √(8.4² m² / (16 · 14)) = 0.561 m over the room inflated by d_limit.
  EXPECT_NEAR(idx.cell_size(), 0.5613, 1e-3);
  EXPECT_TRUE(lists(idx, {4.0, 0.1}, 0));            // near the bottom wall
  EXPECT_FALSE(lists(idx, {4.0, 0.1}, 2));           // the top wall is 7.9 m away
  EXPECT_TRUE(lists(idx, {4.0, 5.0}, 10));           // B's left face x = 4
  EXPECT_TRUE(idx.candidates({3.0, 3.0}).empty());   // open floor
  EXPECT_TRUE(idx.candidates({-1.0, 3.0}).empty());  // outside the grid
  EXPECT_TRUE(idx.candidates({std::nan(""), 3.0}).empty());
}

TEST(SegmentGridIndex, EveryPointWithinDLimitOfASegmentFindsItInItsCell) {
  Rng rng(7);
  const LineMap map = test::random_map(300, 30.0, rng);
  for (const double cell : {0.0, 0.25, 3.0}) {
    const SegmentGridIndex idx(map, {.d_limit = 0.2, .cell_size = cell});
    std::size_t listed = 0;
    for (int k = 0; k < 20000; ++k) {
      const std::uint32_t j = static_cast<std::uint32_t>(rng.uniform() * 300.0);
      const EapRegion& r = idx.regions()[j];
      // A point inside the stadium, often right on its edge.
      const Eigen::Vector2d u = (r.p2() - r.p1()) / r.length();
      const double t = rng.uniform(-0.2, r.length() + 0.2);
      const double h = (k % 2 == 0 ? 0.2 : rng.uniform(-0.2, 0.2));
      Eigen::Vector2d p = r.p1() + t * u + h * Eigen::Vector2d(-u.y(), u.x());
      if (!r.contains(p, RegionRule::kThesis)) continue;
      ++listed;
      EXPECT_TRUE(lists(idx, p, j)) << "cell " << cell << " segment " << j;
    }
    EXPECT_GT(listed, 12000u);
    const auto c = idx.candidates(map.segments[0].p1);
    EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
  }
}

TEST(SegmentGridIndex, RejectsEmptyOrDegenerateMapsAndTooFineGrids) {
  EXPECT_THROW(SegmentGridIndex(LineMap{}), UsageError);
  LineMap bad;
  bad.segments = {{{0, 0}, {1, 0}}, {{2, 2}, {2, 2}}};
  EXPECT_THROW(SegmentGridIndex{bad}, UsageError);
  LineMap wide;
  wide.segments = {{{0, 0}, {1000, 0}}, {{0, 1000}, {1, 1000}}};
  EXPECT_THROW(SegmentGridIndex(wide, {.d_limit = 0.2, .cell_size = 0.1}), UsageError);
  EXPECT_NO_THROW(SegmentGridIndex{wide});  // automatic cell size stays within the cap
  EXPECT_THROW(SegmentGridIndex(sim::room_world(), {.d_limit = 0.0}), UsageError);
}

}  // namespace
}  // namespace locbench::laser
