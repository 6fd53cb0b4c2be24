#pragma once
// Extract-then-match baselines, first half: lines from one scan's points without a map — the
// "cluster → fit" steps of the usual pipeline the thesis compares with (filter → cluster → fit
// → match, Fig. 5.1, O(n²) after Arras/Gutmann). The extractors are pure functions of the
// points and their options:
//   split_and_merge.h      — Nguyen et al. 2007's split-and-merge with adaptive breakpoints
//   agglomerative_lines.h  — Arras & Siegwart 1997's hierarchical clustering in (α, r) space
//   rwht.h                 — Forsberg et al. 1995's Range Weighted Hough Transform
// Points are taken in beam order (as scan_points() gives them). Segmentation works on the
// sensor's polar measurements (range, bearing) and the sensor-frame points built from them, so
// its result does not depend on the frame the lines are finally fitted in.
#include <cstddef>
#include <span>
#include <vector>

#include "algorithms/laser/line_fit.h"
#include "algorithms/laser/scan_points.h"
#include "core/units.h"

namespace locbench::baselines::laser {

// Which coordinates of the ScanPoints a line is fitted in: `robot` for map-free use, `world`
// (the frame of the pose estimate the points were made with) for matching against a map.
enum class LineFrame { robot, world };

struct ExtractedLine {
  std::vector<locbench::laser::ScanPoint> points;  // in beam order, contiguous in the scan
  locbench::laser::LineFit fit;                    // least-squares line of the points in the chosen frame
};

struct ExtractionResult {
  std::vector<ExtractedLine> lines;  // ordered by their first beam
  // Inner-loop work: point–line and point–point tests, model-space distance evaluations,
  // Hough votes and accumulator cells visited (each extractor says which).
  std::size_t work = 0;
};

// Preprocessing shared by the extractors: the adaptive breakpoint detector of Borges & Aldon
// (2004) that Nguyen et al. (2007) put before every algorithm they compared. Consecutive points
// p_{n−1}, p_n are split when ‖p_n − p_{n−1}‖ > r_{n−1}·sin Δφ / sin(λ − Δφ) + 3σ_r, Δφ their
// bearing difference: the farthest apart two returns from one plane seen at incidence up to
// 90° − λ can be, plus noise. Δφ ≥ λ (a long run of missing beams) is always a break.
struct BreakpointOptions {
  double lambda = deg(10.0);     // [rad], in (0, π/2)
  double range_sigma = mm(5.0);  // σ_r [m]: SICK LMS 200 (§5.4); also the point noise of fits
};

// Acceptance of a line, the same as the thesis's EAP matcher (§5.3: C_limit = 5 points, first
// to last more than 200 mm) so that baselines and EAP report the same kind of segment.
struct LineAcceptance {
  std::size_t min_points = 5;  // ≥ 2
  double min_length = 0.2;     // [m] between the first and last point projected on the line
};

// Throw UsageError naming the first field out of its range (options_fields.h).
void validate(const BreakpointOptions& o);
void validate(const LineAcceptance& o);

}  // namespace locbench::baselines::laser
