// Behaviour every extractor must show on hand-made geometry (ray-cast scans of tiny maps).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "baselines/laser/agglomerative_lines.h"
#include "baselines/laser/rwht.h"
#include "baselines/laser/split_and_merge.h"
#include "tests/baselines/laser/laser_scenes.h"

namespace locbench::baselines::laser {
using locbench::laser::scan_points, locbench::laser::ScanPoint;
namespace {

using test::lms_scan, test::segments_map;

struct Extractor {
  std::string name;
  std::function<ExtractionResult(std::span<const ScanPoint>, LineFrame)> run;
};

std::string name_of(const testing::TestParamInfo<Extractor>& info) { return info.param.name; }
void PrintTo(const Extractor& e, std::ostream* os) { *os << e.name; }

class Extractors : public testing::TestWithParam<Extractor> {
 protected:
  ExtractionResult extract(const Scan& scan, const Pose2& pose = Pose2(), LineFrame frame = LineFrame::robot) const {
    points_ = scan_points(scan, pose);
    return GetParam().run(points_, frame);
  }
  mutable std::vector<ScanPoint> points_;
};

TEST_P(Extractors, LShapedCornerGivesTwoLinesSplitExactlyAtTheCorner) {
  // Inside corner at (2, 2), on the 45° beam: wall x = 2 from y = −1, wall y = 2 to x = 0.
  const LineMap map = segments_map({{2, -1, 2, 2}, {2, 2, -1, 2}});
  const ExtractionResult r = extract(lms_scan(map, Pose2()));
  ASSERT_EQ(r.lines.size(), 2u);
  for (const ScanPoint& p : r.lines[0].points) EXPECT_NEAR(p.robot.x(), 2.0, 1e-9) << p.beam;
  for (const ScanPoint& p : r.lines[1].points) EXPECT_NEAR(p.robot.y(), 2.0, 1e-9) << p.beam;
  EXPECT_NEAR(r.lines[0].fit.line.rho, 2.0, 1e-9);
  EXPECT_NEAR(r.lines[0].fit.line.beta, 0.0, 1e-9);
  EXPECT_NEAR(r.lines[1].fit.line.rho, 2.0, 1e-9);
  EXPECT_NEAR(r.lines[1].fit.line.beta, kPi / 2, 1e-9);
  // Every return is on one of the two walls, and every one is used: beams −26.6°…90°.
  EXPECT_EQ(r.lines[0].points.size() + r.lines[1].points.size(), points_.size());
  EXPECT_EQ(points_.size(), 117u);
  // The lines end at the corner, within one beam spacing along a wall seen at 45° from 2.8 m
  // (2.8 m · 1° / cos 45° = 7 cm): the 45° beam hits the corner itself.
  EXPECT_LT((r.lines[0].fit.last - Eigen::Vector2d(2, 2)).norm(), 0.07);
  EXPECT_LT((r.lines[1].fit.first - Eigen::Vector2d(2, 2)).norm(), 0.07);
}

TEST_P(Extractors, StraightWallWithFiveMillimetreNoiseGivesOneLine) {
  // x = 2 for |y| ≤ 3: 113 beams; σ = 5 mm gives σ_ρ ≈ 0.5 mm and σ_β ≈ 0.02°.
  const LineMap map = segments_map({{2, -3, 2, 3}});
  const ExtractionResult r = extract(lms_scan(map, Pose2(), mm(5.0), 7));
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_GE(r.lines[0].points.size(), 110u);
  EXPECT_NEAR(r.lines[0].fit.line.rho, 2.0, mm(3.0));
  EXPECT_NEAR(r.lines[0].fit.line.beta, 0.0, deg(0.1));
  EXPECT_NEAR(r.lines[0].fit.rms, mm(5.0), mm(1.5));
}

TEST_P(Extractors, GapInACollinearWallGivesTwoLines) {
  // x = 2 with a 1 m opening at |y| < 0.5 and nothing behind it (no returns over 28°).
  const LineMap map = segments_map({{2, -3, 2, -0.5}, {2, 0.5, 2, 3}});
  const ExtractionResult r = extract(lms_scan(map, Pose2()));
  ASSERT_EQ(r.lines.size(), 2u);
  for (const ScanPoint& p : r.lines[0].points) EXPECT_LT(p.robot.y(), -0.49);
  for (const ScanPoint& p : r.lines[1].points) EXPECT_GT(p.robot.y(), 0.49);
  for (const ExtractedLine& l : r.lines) {
    EXPECT_NEAR(l.fit.line.rho, 2.0, 1e-9);
    EXPECT_NEAR(l.fit.line.beta, 0.0, 1e-9);
    EXPECT_GE(l.points.size(), 40u);
  }
}

TEST_P(Extractors, FitsInTheRequestedFrameWithTheSameSegmentation) {
  const LineMap map = segments_map({{2, -1, 2, 2}, {2, 2, -1, 2}});
  const Scan scan = lms_scan(map, Pose2(), mm(5.0), 3);
  const Pose2 pose(1.0, 2.0, deg(30.0));
  const ExtractionResult robot = extract(scan, pose, LineFrame::robot);
  const ExtractionResult world = extract(scan, pose, LineFrame::world);
  ASSERT_EQ(robot.lines.size(), 2u);
  ASSERT_EQ(world.lines.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(robot.lines[i].points.size(), world.lines[i].points.size());
    const LineParams expected = test::transform_line(robot.lines[i].fit.line, pose);
    const test::LineError e = test::line_error(world.lines[i].fit.line, expected);
    EXPECT_LT(e.rho, 1e-9);
    EXPECT_LT(e.beta, 1e-9);
  }
}

TEST_P(Extractors, TooFewPointsGiveNoLines) {
  EXPECT_TRUE(GetParam().run({}, LineFrame::robot).lines.empty());
  const LineMap map = segments_map({{2, -0.05, 2, 0.05}});  // 3 beams
  const ExtractionResult r = extract(lms_scan(map, Pose2()));
  EXPECT_EQ(points_.size(), 3u);
  EXPECT_TRUE(r.lines.empty());
}

INSTANTIATE_TEST_SUITE_P(
    AllExtractors, Extractors,
    testing::Values(
        Extractor{"split_and_merge", [](std::span<const ScanPoint> p, LineFrame f) { return split_and_merge(p, f); }},
        Extractor{"agglomerative", [](std::span<const ScanPoint> p, LineFrame f) { return agglomerative_lines(p, f); }},
        Extractor{"rwht", [](std::span<const ScanPoint> p, LineFrame f) { return rwht_lines(p, f).extraction; }}),
    name_of);

}  // namespace
}  // namespace locbench::baselines::laser
