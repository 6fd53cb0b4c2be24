#include "baselines/laser/rwht.h"

#include <gtest/gtest.h>

#include <iostream>

#include "datasets/sim/worlds.h"
#include "tests/baselines/laser/laser_scenes.h"

namespace locbench::baselines::laser {
using locbench::laser::scan_points, locbench::laser::ScanPoint;
namespace {

const Pose2 kThesisPose(2.0, 1.0, deg(46.0));

TEST(Rwht, VotesMeasureAWallsLengthNotItsPointCount) {
  // Walls facing the sensor over the same ±18.3° (37 beams): 2 m long at 3.025 m and 4 m long
  // at 6.025 m (both in the middle of a 5 cm range bin). Plain counting would tie them.
  const LineMap near = test::segments_map({{3.025, -1, 3.025, 1}});
  const LineMap far = test::segments_map({{6.025, -2, 6.025, 2}});
  const RwhtExtraction a = rwht_lines(scan_points(test::lms_scan(near, Pose2()), Pose2()), LineFrame::robot);
  const RwhtExtraction b = rwht_lines(scan_points(test::lms_scan(far, Pose2()), Pose2()), LineFrame::robot);
  ASSERT_EQ(a.extraction.lines.size(), 1u);
  ASSERT_EQ(b.extraction.lines.size(), 1u);
  EXPECT_EQ(a.extraction.lines[0].points.size(), 37u);
  EXPECT_EQ(b.extraction.lines[0].points.size(), 37u);
  // Each vote is range × 1° beam spacing; the peak cell holds all of them: Σ R·Δφ ≈ length.
  double expected_a = 0.0;
  for (const ScanPoint& p : a.extraction.lines[0].points) expected_a += p.range * deg(1.0);
  EXPECT_NEAR(a.peaks[0].votes, expected_a, 1e-9);
  EXPECT_NEAR(a.peaks[0].votes, 2.0, 0.02);
  EXPECT_NEAR(b.peaks[0].votes / a.peaks[0].votes, 2.0, 0.01);
  EXPECT_NEAR(a.peaks[0].cell.rho, 3.025, 1e-9);  // the bin [3.00, 3.05)
  EXPECT_NEAR(std::abs(a.peaks[0].cell.beta), deg(0.5), 1e-9);
}

struct BinTrial {
  double peak_distance = 0.0;  // mean over lines of the largest point distance to the cell line
  double peak_rho = 0.0;       // mean |Δρ| of the cell line against the true line
  double peak_beta = 0.0;      // mean |Δβ|
  double fit_rho = 0.0;        // mean |Δρ| of the least-squares refit against the true line
  double fit_beta = 0.0;       // mean |Δβ|
  std::size_t cells = 0, work = 0, lines = 0;
};

BinTrial run_bins(const Scan& scan, const LineMap& room, double angle_bin, double range_bin) {
  RwhtOptions o;
  o.angle_bin = angle_bin;
  o.range_bin = range_bin;
  const std::vector<ScanPoint> points = scan_points(scan, Pose2());  // sensor = robot frame
  const RwhtExtraction r = rwht_lines(points, LineFrame::robot, o);
  const std::vector<int> truth = test::true_segment_of_beams(room, kThesisPose, scan);
  BinTrial t;
  t.cells = r.cells;
  double r_max = 0.0;
  for (const ScanPoint& p : points) r_max = std::max(r_max, p.range);
  const auto n_alpha = static_cast<std::size_t>(std::lround(2.0 * kPi / angle_bin));
  EXPECT_EQ(r.cells, n_alpha * (static_cast<std::size_t>(r_max / range_bin) + 1));
  t.work = r.extraction.work;
  t.lines = r.extraction.lines.size();
  for (std::size_t i = 0; i < r.extraction.lines.size(); ++i) {
    const ExtractedLine& l = r.extraction.lines[i];
    double worst = 0.0;
    for (const ScanPoint& p : l.points) {
      worst = std::max(worst, std::abs(signed_distance_to_line(r.peaks[r.line_peak[i]].cell, p.robot)));
    }
    t.peak_distance += worst;
    const auto seg = static_cast<std::size_t>(truth[l.points[l.points.size() / 2].beam]);
    const LineParams truth_line = test::transform_line(room.segments[seg].line(), kThesisPose.inverse());
    const test::LineError e = test::line_error(l.fit.line, truth_line);
    t.fit_rho += e.rho;
    t.fit_beta += e.beta;
    const test::LineError c = test::line_error(r.peaks[r.line_peak[i]].cell, truth_line);
    t.peak_rho += c.rho;
    t.peak_beta += c.beta;
  }
  const double n = static_cast<double>(t.lines);
  t.peak_distance /= n;
  t.fit_rho /= n;
  t.fit_beta /= n;
  t.peak_rho /= n;
  t.peak_beta /= n;
  std::cout << "bins " << to_deg(angle_bin) << " deg x " << to_mm(range_bin) << " mm: " << t.lines
            << " lines, cell |drho| " << to_mm(t.peak_rho) << " mm |dbeta| " << to_deg(t.peak_beta)
            << " deg, cell line to points " << to_mm(t.peak_distance) << " mm, LS refit |drho| " << to_mm(t.fit_rho)
            << " mm |dbeta| " << to_deg(t.fit_beta) << " deg, " << t.cells << " cells, work " << t.work << "\n";
  return t;
}

TEST(Rwht, FinerBinsPlaceLinesCloserAndCoarserBinsCostFewerCells) {
  const LineMap room = sim::room_world();
  const Scan scan = test::lms_scan(room, kThesisPose, mm(5.0), 5);
  const BinTrial fine = run_bins(scan, room, deg(0.25), 0.0125);
  const BinTrial normal = run_bins(scan, room, deg(1.0), 0.05);
  const BinTrial coarse = run_bins(scan, room, deg(4.0), 0.2);
  // Accuracy of the bins themselves: the cell-centre line's distance from its points.
  EXPECT_LT(fine.peak_distance, normal.peak_distance);
  EXPECT_LT(normal.peak_distance, coarse.peak_distance);
  // Cost: a quarter of both bins is 16× the cells; votes grow with the angle bins.
  EXPECT_GT(fine.cells, 15 * normal.cells);
  EXPECT_GT(normal.cells, 15 * coarse.cells);
  EXPECT_GT(fine.work, 5 * normal.work);
  EXPECT_GT(normal.work, 3 * coarse.work);
  EXPECT_LT(fine.peak_rho, normal.peak_rho);
  EXPECT_LT(normal.peak_rho, coarse.peak_rho);
  EXPECT_LT(fine.peak_beta, normal.peak_beta);
  EXPECT_LT(normal.peak_beta, coarse.peak_beta);
  // What the matcher uses is the least-squares refit of each peak's points: as long as the
  // bins find every wall and the band catches its points, bin size no longer matters (same
  // points, same fit) — even 4° × 20 cm bins find all 9 walls of this scan.
  for (const BinTrial& t : {fine, normal, coarse}) {
    EXPECT_EQ(t.lines, 9u);
    EXPECT_NEAR(t.fit_rho, normal.fit_rho, 1e-12);
    EXPECT_NEAR(t.fit_beta, normal.fit_beta, 1e-12);
  }
}

// The accumulator's cells are kept per thread from scan to scan (a fine grid is released): what a
// scan gives must not depend on the scans extracted before it, on any grid.
TEST(Rwht, TheLinesOfAScanDoNotDependOnTheScansExtractedBefore) {
  const LineMap room = sim::room_world();
  const auto points_at = [&](const Pose2& pose) {
    return scan_points(test::lms_scan(room, pose, mm(5.0), 3), Pose2());
  };
  const auto a = points_at(kThesisPose), b = points_at(Pose2(3.0, 2.0, deg(-20.0)));
  RwhtOptions fine;
  fine.angle_bin = deg(0.05);  // 7,200 × ~1,600 cells: beyond what is kept for the next scan
  fine.range_bin = 0.005;
  const RwhtExtraction first = rwht_lines(a, LineFrame::robot);
  rwht_lines(b, LineFrame::robot, fine);
  rwht_lines(b, LineFrame::robot);
  const RwhtExtraction again = rwht_lines(a, LineFrame::robot);
  ASSERT_EQ(again.peaks.size(), first.peaks.size());
  for (std::size_t i = 0; i < first.peaks.size(); ++i) {
    EXPECT_EQ(again.peaks[i].votes, first.peaks[i].votes);
    EXPECT_EQ(again.peaks[i].cell.rho, first.peaks[i].cell.rho);
    EXPECT_EQ(again.peaks[i].cell.beta, first.peaks[i].cell.beta);
  }
  ASSERT_EQ(again.extraction.lines.size(), first.extraction.lines.size());
  for (std::size_t i = 0; i < first.extraction.lines.size(); ++i) {
    EXPECT_EQ(again.extraction.lines[i].points.size(), first.extraction.lines[i].points.size());
  }
}

}  // namespace
}  // namespace locbench::baselines::laser
