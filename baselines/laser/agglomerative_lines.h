#pragma once
// Line extraction by hierarchical agglomerative clustering in line-model space, after Arras &
// Siegwart ("Feature extraction and scene interpretation for map-based navigation and map
// building", SPIE Mobile Robotics XII, 1997) — the thesis's [101], which it describes as
// "clustering the scan with a Mahalanobis distance matrix by hierarchical clustering", and the
// clustering step it names as what makes the usual pipeline O(n²) (§5.1).
//   1. filter: adaptive breakpoints (as in split_and_merge.h) cut the scan into runs; runs too
//      short to hold an accepted line are dropped (isolated and spurious returns);
//   2. local lines: every point gets the least-squares line of the `window` points around it
//      (within its run) with the covariance of (α, r) from σ_r; windows that fail a χ² test
//      of their residuals (they straddle a corner or an edge) seed no cluster;
//   3. clustering: each local line is a cluster; the two clusters closest in (α, r) by the
//      Mahalanobis distance d² = Δᵀ(C_i + C_j)⁻¹Δ are merged — their line refitted to all the
//      points their windows covered — until no pair has d² below the χ²₂ quantile;
//   4. points left out in 2 join the cluster of an adjacent point whose line is within
//      `assign_distance`; every cluster is cut into pieces contiguous in the scan (collinear
//      walls end up in one cluster), and each piece is least-squares fitted and accepted.
// Variant and why: the full model-space clustering (every pair of clusters compared, not only
// neighbours) because that is the method the thesis cites and its cost claim is about; it is
// O(m²) distance evaluations to start and O(m) per merge with cached nearest neighbours (m ≤ n
// local lines), so O(n²) overall. Nguyen et al.'s "line regression" restricts the same idea to
// adjacent windows (O(n·window)) and is not what [101] describes. (α, r) are measured in the
// sensor frame, where no wall passes through the origin, so α is never ambiguous.
// work = model-space distance evaluations + points visited by fits and assignment tests.
#include <span>

#include "baselines/laser/line_extraction.h"

namespace locbench::baselines::laser {

struct AgglomerativeOptions {
  BreakpointOptions breakpoints;  // range_sigma is also the σ of a point across a line
  LineAcceptance acceptance;
  // Points per local line (≥ 3): acceptance.min_points, so the shortest acceptable wall (five
  // beams at grazing incidence, like the room's obstacle C from the thesis pose) still gets a
  // window that does not straddle a corner.
  int window = 5;
  double window_confidence = 0.99;  // local line kept if Σr²/σ_r² ≤ χ²(window − 2) quantile
  // Clusters merge while d² < the χ²(2) quantile (23.0). Every cluster is tested against its
  // nearest one until it stops, so the per-test false rejection must be far below 1/(local
  // lines on a wall): at 0.99 (9.21) 22% of noisy 113-point walls split in two (measured,
  // 200 seeds), at 0.9999 1.5%, at 0.99999 none — while 90° corners differ by > 100σ.
  double merge_confidence = 0.99999;
  // Added to every cluster's (α, r) standard deviations so that merging does not stall on
  // walls that are not perfectly flat once clusters hold hundreds of points.
  double model_sigma_alpha = deg(0.1);  // [rad]
  double model_sigma_r = mm(2.0);       // [m]
  double assign_distance = 0.02;        // [m] ≈ 4σ_r
  int max_gap_points = 2;               // a line may skip this many points of its run (≥ 0)
};

// Throws UsageError naming the first invalid option.
void validate(const AgglomerativeOptions& o);

ExtractionResult agglomerative_lines(std::span<const locbench::laser::ScanPoint> points, LineFrame frame,
                                     const AgglomerativeOptions& options = {});

}  // namespace locbench::baselines::laser
