#include "baselines/laser/line_to_map_matching.h"

#include <gtest/gtest.h>

#include <functional>

#include "core/errors.h"
#include "tests/baselines/laser/laser_scenes.h"

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::ScanPoint;
namespace {

// An extracted line of `count` world points evenly from a to b, beams first_beam, first_beam+1…
ExtractedLine line_between(Eigen::Vector2d a, Eigen::Vector2d b, std::size_t first_beam, std::size_t count = 10) {
  ExtractedLine l;
  std::vector<Eigen::Vector2d> pts;
  for (std::size_t i = 0; i < count; ++i) {
    ScanPoint p;
    p.beam = first_beam + i;
    p.world = a + (b - a) * static_cast<double>(i) / static_cast<double>(count - 1);
    p.robot = p.world;
    l.points.push_back(p);
    pts.push_back(p.world);
  }
  l.fit = fit_line(pts);
  return l;
}

TEST(LineToMapMatching, LineOnASegmentMatchesItWithItsPointsAndFit) {
  const LineMap map = test::segments_map({{0, 3, 4, 3}, {4, 0, 4, 3}});
  const std::vector<ExtractedLine> lines{line_between({1, 3}, {3, 3}, 0)};
  const LineToMapMatches m = match_lines_to_map(lines, map, {2, 1});
  ASSERT_EQ(m.matches.size(), 1u);
  EXPECT_EQ(m.matches[0].map_segment, 0u);
  EXPECT_EQ(m.matches[0].points.size(), 10u);
  EXPECT_NEAR(m.matches[0].fit.line.rho, 3.0, 1e-12);
  EXPECT_EQ(m.segment_of[0], std::optional<std::size_t>(0));
  EXPECT_EQ(m.work, 2u);  // one line × two segments
}

TEST(LineToMapMatching, ParallelWallOneMetreAwayIsGatedOutByDeltaRho) {
  const LineMap map = test::segments_map({{0, 4, 4, 4}});
  const std::vector<ExtractedLine> lines{line_between({1, 3}, {3, 3}, 0), line_between({1, 3.8}, {3, 3.8}, 20)};
  const LineToMapMatches m = match_lines_to_map(lines, map, {2, 1});
  EXPECT_FALSE(m.segment_of[0].has_value());                  // Δρ = 1 m > 0.3 m
  EXPECT_EQ(m.segment_of[1], std::optional<std::size_t>(0));  // Δρ = 0.2 m
}

TEST(LineToMapMatching, LineTurnedMoreThanTenDegreesIsGatedOutByDeltaBeta) {
  const LineMap map = test::segments_map({{0, 3, 4, 3}});
  const double t = std::tan(deg(12.0));
  const std::vector<ExtractedLine> lines{line_between({1, 3 - t}, {3, 3 + t}, 0)};
  EXPECT_FALSE(match_lines_to_map(lines, map, {2, 3}).segment_of[0].has_value());
  const double u = std::tan(deg(8.0));
  const std::vector<ExtractedLine> near{line_between({1, 3 - u}, {3, 3 + u}, 0)};
  EXPECT_TRUE(match_lines_to_map(near, map, {2, 3}).segment_of[0].has_value());
}

TEST(LineToMapMatching, CollinearLineBeyondTheSegmentEndIsGatedOutByOverlap) {
  // Same infinite line, but the extracted piece lies 1–2 m past the end (tolerance 0.3 m).
  const LineMap map = test::segments_map({{0, 3, 4, 3}});
  const std::vector<ExtractedLine> past{line_between({5, 3}, {6, 3}, 0)};
  EXPECT_FALSE(match_lines_to_map(past, map, {2, 1}).segment_of[0].has_value());
  // Partly past the end: 3.5–5.0 has 0.8 of 1.5 m (53%) before 4.0 + 0.3 m and matches,
  // 3.9–5.0 has 0.4 of 1.1 m (36%) and does not (50% required).
  const std::vector<ExtractedLine> most{line_between({3.5, 3}, {5.0, 3}, 0)};
  EXPECT_TRUE(match_lines_to_map(most, map, {2, 1}).segment_of[0].has_value());
  const std::vector<ExtractedLine> less{line_between({3.9, 3}, {5.0, 3}, 0)};
  EXPECT_FALSE(match_lines_to_map(less, map, {2, 1}).segment_of[0].has_value());
}

TEST(LineToMapMatching, TwoLinesOnOneSegmentArePooledInBeamOrder) {
  const LineMap map = test::segments_map({{0, 3, 6, 3}});
  const std::vector<ExtractedLine> lines{line_between({4, 3}, {5, 3}, 30, 5), line_between({1, 3}, {2, 3}, 0, 5)};
  const LineToMapMatches m = match_lines_to_map(lines, map, {3, 0});
  ASSERT_EQ(m.matches.size(), 1u);
  ASSERT_EQ(m.matches[0].points.size(), 10u);
  for (std::size_t i = 1; i < 10; ++i) {
    EXPECT_LT(m.matches[0].points[i - 1].beam, m.matches[0].points[i].beam);
  }
  EXPECT_NEAR((m.matches[0].fit.first - Eigen::Vector2d(1, 3)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.matches[0].fit.last - Eigen::Vector2d(5, 3)).norm(), 0.0, 1e-12);
}

TEST(LineToMapMatching, OfTwoPassingSegmentsTheCheaperOneWins) {
  // Wall y = 3 and a 5°-turned wall through the same stretch: both pass, y = 3 costs 0.
  const double t = std::tan(deg(5.0));
  const LineMap map = test::segments_map({{0, 3 - 2 * t, 4, 3 + 2 * t}, {0, 3, 4, 3}});
  const std::vector<ExtractedLine> lines{line_between({1, 3}, {3, 3}, 0)};
  EXPECT_EQ(match_lines_to_map(lines, map, {2, 1}).segment_of[0], std::optional<std::size_t>(1));
}

TEST(LineToMapMatching, WallThroughTheWorldOriginMatchesWhicheverWayItsNormalPoints) {
  // The room's bottom wall y = 0 has ρ = 0: a fit may give β = −90° where the map says +90°.
  const LineMap map = test::segments_map({{0, 0, 8, 0}});
  ExtractedLine l = line_between({3, 0.01}, {5, -0.01}, 0);
  l.fit.line = {1e-6, -kPi / 2};
  const std::vector<ExtractedLine> lines{l};
  EXPECT_EQ(match_lines_to_map(lines, map, {2, 1}).segment_of[0], std::optional<std::size_t>(0));
  EXPECT_EQ(match_lines_to_map(lines, map, {0, 0}).segment_of[0], std::optional<std::size_t>(0));
}

TEST(LineToMapMatching, DeltaRhoIsMeasuredFromThePivotNotTheWorldOrigin) {
  // Wall x = 40 seen from (35, 30) with the heading 3° off, i.e. the scan rotated 3° about the
  // sensor: from the sensor the wall stays 5 m away (Δρ = 0); measured from the world origin
  // its ρ would move by 35·(cos 3° − 1) + 30·sin 3° ≈ 1.52 m, far outside the 0.3 m gate.
  const LineMap map = test::segments_map({{40, -5, 40, 35}});
  const Pose2 about_sensor = Pose2(35, 30, deg(3.0)) * Pose2(-35, -30, 0.0);
  const std::vector<ExtractedLine> lines{
      line_between(about_sensor * Eigen::Vector2d(40, 28), about_sensor * Eigen::Vector2d(40, 32), 0)};
  EXPECT_EQ(match_lines_to_map(lines, map, {35, 30}).segment_of[0], std::optional<std::size_t>(0));
  EXPECT_FALSE(match_lines_to_map(lines, map, {0, 0}).segment_of[0].has_value());
}

TEST(LineToMapMatching, InvalidOptionsThrowUsageError) {
  const LineMap map = test::segments_map({{0, 0, 1, 0}});
  for (auto mutate : std::vector<std::function<void(LineMatchOptions&)>>{
           [](LineMatchOptions& o) { o.max_delta_rho = 0.0; }, [](LineMatchOptions& o) { o.max_delta_rho = -0.1; },
           [](LineMatchOptions& o) { o.max_delta_beta = 0.0; }, [](LineMatchOptions& o) { o.min_overlap = 0.0; },
           [](LineMatchOptions& o) { o.min_overlap = 1.5; }, [](LineMatchOptions& o) { o.end_tolerance = -0.01; }}) {
    LineMatchOptions o;
    mutate(o);
    EXPECT_THROW(match_lines_to_map({}, map, {0, 0}, o), UsageError);
  }
}

}  // namespace
}  // namespace locbench::baselines::laser
