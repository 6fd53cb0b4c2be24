#pragma once
// Split-and-merge line extraction as compared by Nguyen, Gächter, Martinelli, Tomatis and
// Siegwart ("A comparison of line extraction algorithms using 2D range data for indoor mobile
// robotics", Autonomous Robots 23, 2007), who found it the fastest and among the most correct:
//   0. preprocessing: adaptive breakpoints (Borges & Aldon 2004) cut the scan into runs;
//   1. split, per run: fit a least-squares line to a set; if its largest perpendicular
//      residual exceeds `split_distance`, split the set at its farthest point and recurse;
//   2. merge: adjacent sets of a run whose union fits one line within `split_distance` are
//      merged (collinear neighbours);
//   3. a point at the boundary of two adjacent sets goes to the one whose line (fitted
//      without it) is nearer — the split leaves the split point on the left whichever wall it
//      lies on, and a point just past a corner is within split_distance of both walls;
//      least-squares refit of every set; sets with too few points or too short are dropped.
// The split point is the interior point farthest from the chord through the set's end points
// (Ramer / iterative end-point fit): the least-squares line of an L with equal legs is as far
// from the corner as from both ends, so splitting at the point farthest from it can cut off an
// end point instead of the corner. Whether to split is still decided on the least-squares line.
// Complexity: O(n log n) for balanced splits, O(n²) in the worst case (one point cut per split).
// work = points visited by fits and distance tests.
#include <span>

#include "baselines/laser/line_extraction.h"

namespace locbench::baselines::laser {

struct SplitAndMergeOptions {
  BreakpointOptions breakpoints;
  LineAcceptance acceptance;
  // Largest residual a line may keep [m]: 5σ of the LMS 200's σ_r = 5 mm, so noise alone
  // splits a 181-point wall with probability ~1e-4, while the points past a corner leave the
  // line by far more (one beam past a 90° corner at 3 m: ≈ 5 cm).
  double split_distance = 0.025;
};

// Throws UsageError naming the first invalid option.
void validate(const SplitAndMergeOptions& o);

ExtractionResult split_and_merge(std::span<const locbench::laser::ScanPoint> points, LineFrame frame,
                                 const SplitAndMergeOptions& options = {});

}  // namespace locbench::baselines::laser
