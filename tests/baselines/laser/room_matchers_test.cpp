// The three extract-then-match matchers on the thesis's room (§5.4) from its pose
// (2.0 m, 1.0 m, 46°), against the visible segments computed by ray casting.
#include <gtest/gtest.h>

#include <memory>
#include <set>

#include "baselines/laser/extract_then_match.h"
#include "datasets/sim/worlds.h"
#include "tests/baselines/laser/laser_scenes.h"

namespace locbench::baselines::laser {
using locbench::laser::MatchResult, locbench::laser::ScanPoint, locbench::laser::SegmentMatch,
    locbench::laser::SegmentMatcher;
namespace {

const Pose2 kThesisPose(2.0, 1.0, deg(46.0));

struct MatcherCase {
  std::string name;
  std::shared_ptr<const SegmentMatcher> matcher;
  std::function<ExtractionResult(const Scan&)> extract_lines;
};

std::string name_of(const testing::TestParamInfo<MatcherCase>& info) { return info.param.name; }
void PrintTo(const MatcherCase& c, std::ostream* os) { *os << c.name; }

std::set<std::size_t> matched(const MatchResult& r) {
  std::set<std::size_t> s;
  for (const SegmentMatch& m : r.matches) s.insert(m.map_segment);
  return s;
}

class RoomMatchers : public testing::TestWithParam<MatcherCase> {
 protected:
  const LineMap room_ = sim::room_world();
};

TEST_P(RoomMatchers, NameIsStable) { EXPECT_EQ(GetParam().matcher->name(), GetParam().name); }

TEST_P(RoomMatchers, NoiseFreeScanAtTheThesisPoseMatchesEveryVisibleSegmentExactly) {
  const Scan scan = test::lms_scan(room_, kThesisPose);
  const std::set<std::size_t> visible = test::visible_segments(room_, kThesisPose, scan);
  // As the world's header says, 9 of the 14 segments are in view, each with ≥ 5 beams.
  EXPECT_EQ(visible, (std::set<std::size_t>{0, 1, 2, 3, 4, 7, 10, 11, 12}));
  const MatchResult r = GetParam().matcher->match(scan, room_, kThesisPose);
  EXPECT_EQ(matched(r), visible);
  EXPECT_GT(r.work, 0u);
  const std::vector<int> truth = test::true_segment_of_beams(room_, kThesisPose, scan);
  for (const SegmentMatch& m : r.matches) {
    const test::LineError e = test::line_error(m.fit.line, room_.segments[m.map_segment].line());
    EXPECT_LT(e.rho, mm(1.0)) << "segment " << m.map_segment;
    EXPECT_LT(e.beta, deg(0.05)) << "segment " << m.map_segment;
    EXPECT_GE(m.points.size(), 5u);
    for (const ScanPoint& p : m.points) {
      // every point on the matched segment (a corner beam may be credited to its neighbour)
      EXPECT_LT(distance_to_segment(room_.segments[m.map_segment], p.world), 1e-9)
          << "segment " << m.map_segment << " beam " << p.beam << " truly on " << truth[p.beam];
    }
  }
}

TEST_P(RoomMatchers, NoisyScanWithAnEstimateOffByTenCentimetresAndThreeDegreesStillMatches) {
  const Scan scan = test::lms_scan(room_, kThesisPose, mm(5.0), 11);
  const std::set<std::size_t> visible = test::visible_segments(room_, kThesisPose, scan);
  const Pose2 estimate(kThesisPose.x + 0.1, kThesisPose.y + 0.1, kThesisPose.theta - deg(3.0));
  const MatchResult r = GetParam().matcher->match(scan, room_, estimate);
  EXPECT_EQ(matched(r), visible);
  const std::vector<int> truth = test::true_segment_of_beams(room_, kThesisPose, scan);
  for (const SegmentMatch& m : r.matches) {
    std::size_t right = 0;
    for (const ScanPoint& p : m.points) right += truth[p.beam] == static_cast<int>(m.map_segment);
    EXPECT_GE(static_cast<double>(right), 0.95 * static_cast<double>(m.points.size())) << "segment " << m.map_segment;
  }
}

TEST_P(RoomMatchers, MapFreeExtractionGivesRobotFrameLinesOfTheVisibleWalls) {
  const Scan scan = test::lms_scan(room_, kThesisPose);
  const ExtractionResult r = GetParam().extract_lines(scan);
  const std::set<std::size_t> visible = test::visible_segments(room_, kThesisPose, scan);
  ASSERT_GE(r.lines.size(), visible.size());
  const std::vector<int> truth = test::true_segment_of_beams(room_, kThesisPose, scan);
  std::set<std::size_t> seen;
  for (const ExtractedLine& l : r.lines) {
    // the line of the wall its middle point is on, brought into the robot frame
    const auto seg = static_cast<std::size_t>(truth[l.points[l.points.size() / 2].beam]);
    const LineParams expected = test::transform_line(room_.segments[seg].line(), kThesisPose.inverse());
    const test::LineError e = test::line_error(l.fit.line, expected);
    EXPECT_LT(e.rho, mm(1.0)) << "segment " << seg;
    EXPECT_LT(e.beta, deg(0.05)) << "segment " << seg;
    seen.insert(seg);
  }
  EXPECT_EQ(seen, visible);
}

INSTANTIATE_TEST_SUITE_P(
    AllMatchers, RoomMatchers,
    testing::Values(MatcherCase{"split_and_merge", std::make_shared<SplitAndMergeMatcher>(),
                                [](const Scan& s) { return SplitAndMergeMatcher().extract_lines(s); }},
                    MatcherCase{"agglomerative", std::make_shared<AgglomerativeMatcher>(),
                                [](const Scan& s) { return AgglomerativeMatcher().extract_lines(s); }},
                    MatcherCase{"rwht", std::make_shared<RwhtMatcher>(),
                                [](const Scan& s) { return RwhtMatcher().extract_lines(s); }}),
    name_of);

}  // namespace
}  // namespace locbench::baselines::laser
