#pragma once
// The Range Weighted Hough Transform of Forsberg, Larsson & Wernersson ("Mobile robot
// navigation using the range-weighted Hough transform", IEEE Robotics & Automation Magazine
// 2(1), 1995) — the thesis's baseline of §1.2.1.4, whose accuracy and cost it says depend on
// the angle and range bin sizes.
//   1. vote: an accumulator over (α, r) in the sensor frame, α ∈ [−π, π) in bins of
//      `angle_bin`, r ∈ [0, largest range] in bins of `range_bin`; each point adds, for every
//      α column, its weight to the cell of r = x cos α + y sin α. The weight is range × the
//      beam spacing Δφ (Forsberg's range weighting: a beam at range R samples R·Δφ of a surface
//      facing it, so a wall's votes measure its length, not how close it is);
//   2. peaks: cells that are the maximum of their (2k+1)² neighbourhood (non-maximum
//      suppression, α wrapping around) and, with their two range neighbours, hold at least
//      `min_peak_votes` and acceptance.min_points voters (so a short line whose votes straddle
//      a range-bin boundary is not lost), strongest first;
//   3. per peak: the points within the cell's band (half a range bin + R·Δα/2 + 3σ_r of the
//      cell-centre line); their largest contiguous stretch, trimmed one point at a time (the
//      first, the last or the farthest, whichever leaves the best fit: the band also catches
//      stray points of walls crossing it) until all are within `inlier_distance`, is
//      least-squares fitted; then the points within `inlier_distance` of the fit are taken and
//      refitted (up to 3 rounds). A peak whose line is within one bin of a line already found
//      is that line's second peak and is skipped. Points held by an earlier line stay with it,
//      except the end points of its stretch of the scan that lie nearer to this line (both
//      fitted without the point) — else the stronger line keeps the first beam past a corner;
//   4. each line is cut into pieces contiguous in the scan and accepted or dropped; a point
//      left without a line joins a scan neighbour's line within `inlier_distance`.
// Cost: n·N_α votes + N_α·N_r cells + O(n) per peak (O(k²) when k points must be trimmed), so
// quartering both bin sizes gives 16× the cells. The lines come from the least-squares refit;
// the cell-centre (α, r) of each line's peak is reported too — the accuracy of the bins alone.
// work = votes cast + accumulator cells visited + point–line tests.
#include <span>

#include "baselines/laser/line_extraction.h"

namespace locbench::baselines::laser {

struct RwhtOptions {
  BreakpointOptions breakpoints;  // contiguity of pieces; range_sigma widens the peak band
  LineAcceptance acceptance;
  double angle_bin = deg(1.0);    // [rad]: the LMS 200's beam spacing
  double range_bin = 0.05;        // [m]: ≈ the spread of a 4 m wall's votes at ½° off its α
  double min_peak_votes = 0.2;    // [m] of range-weighted votes: acceptance.min_length
  int nms_radius = 2;             // k, in bins, both axes (≥ 1)
  double inlier_distance = 0.02;  // [m] ≈ 4σ_r
  int max_gap_points = 2;         // a line may skip this many points of its run (≥ 0)
};

// Throws UsageError naming the first invalid option.
void validate(const RwhtOptions& o);

struct RwhtPeak {
  LineParams cell;     // the cell centre's line (ρ = r, β = α), sensor frame
  double votes = 0.0;  // range-weighted [m]
};

struct RwhtExtraction {
  ExtractionResult extraction;
  std::vector<std::size_t> line_peak;  // lines[i] came from peaks[line_peak[i]]
  std::vector<RwhtPeak> peaks;         // every peak that produced a line
  std::size_t cells = 0;               // N_α · N_r
};

RwhtExtraction rwht_lines(std::span<const locbench::laser::ScanPoint> points, LineFrame frame,
                          const RwhtOptions& options = {});

}  // namespace locbench::baselines::laser
