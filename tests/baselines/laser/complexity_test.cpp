// How each extractor's work grows with the number of points on one straight wall: the
// agglomerative clustering compares every pair of local lines (O(n²), the thesis's point
// about the usual pipeline), split-and-merge fits each point a few times, RWHT votes n × N_α.
#include <gtest/gtest.h>

#include <iostream>

#include "baselines/laser/agglomerative_lines.h"
#include "baselines/laser/rwht.h"
#include "baselines/laser/split_and_merge.h"
#include "tests/baselines/laser/laser_scenes.h"

namespace locbench::baselines::laser {
using locbench::laser::scan_points, locbench::laser::ScanPoint;
namespace {

struct Works {
  std::size_t split_and_merge = 0, agglomerative = 0, rwht = 0, points = 0;
};

Works works_on_wall(int beams) {
  const LineMap map = test::segments_map({{2, -3, 2, 3}});
  const std::vector<ScanPoint> p = scan_points(test::lms_scan(map, Pose2(), mm(5.0), 9, beams), Pose2());
  Works w;
  w.points = p.size();
  w.split_and_merge = split_and_merge(p, LineFrame::robot).work;
  w.agglomerative = agglomerative_lines(p, LineFrame::robot).work;
  w.rwht = rwht_lines(p, LineFrame::robot).extraction.work;
  std::cout << w.points << " points: split_and_merge " << w.split_and_merge << ", agglomerative " << w.agglomerative
            << ", rwht " << w.rwht << "\n";
  return w;
}

TEST(ExtractorWork, DoublingThePointsQuadruplesClusteringButNotSplitAndMerge) {
  const Works one = works_on_wall(181);  // 1° spacing: 113 points on the wall
  const Works two = works_on_wall(361);  // 0.5°: 225 points
  ASSERT_EQ(one.points, 113u);
  ASSERT_EQ(two.points, 225u);
  const auto ratio = [](std::size_t a, std::size_t b) { return static_cast<double>(b) / static_cast<double>(a); };
  EXPECT_GT(ratio(one.agglomerative, two.agglomerative), 3.0);
  EXPECT_LT(ratio(one.split_and_merge, two.split_and_merge), 2.5);
  EXPECT_LT(ratio(one.rwht, two.rwht), 2.1);
  EXPECT_GT(one.agglomerative, 10 * one.split_and_merge);
}

}  // namespace
}  // namespace locbench::baselines::laser
