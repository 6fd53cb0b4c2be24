#pragma once
// Extract-then-match baselines, second half: extracted lines (world frame, under the pose
// estimate) to map segments — the "match" step of the usual pipeline (thesis Fig. 5.1), in the
// manner of Gutmann's LineMatch and Arras's matching of line features:
//   gates: |Δρ| ≤ max_delta_rho and |Δβ| ≤ max_delta_beta, with ρ measured from the pivot (the
//          estimated sensor position) rather than the world origin, so that a heading error
//          does not turn into a ρ error growing with the distance to the origin; the two
//          normal forms (ρ, β) and (−ρ, β + π) of a line are both tried, so lines passing close
//          to the pivot compare correctly;
//          overlap: the extracted segment projected on the map segment's direction must lie on
//          the map segment (extended by `end_tolerance` at both ends) for at least
//          `min_overlap` of its length;
//   cost:  (Δρ / max_delta_rho)² + (Δβ / max_delta_beta)²; each extracted line goes to the
//          passing segment of least cost (ties: lower segment index);
//   merge: lines that go to the same segment pool their points (beam order) into one
//          SegmentMatch, refitted by least squares on the world points.
// work = line–segment tests (lines × segments).
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "baselines/laser/line_extraction.h"
#include "core/line_map.h"
#include "core/units.h"

namespace locbench::baselines::laser {

struct LineMatchOptions {
  // Room for a pose estimate off by ~0.15 m and ~5° (the EKF's prior of Chapter 6 is far
  // better) while parallel map lines 1 m apart, as in the room, stay apart.
  double max_delta_rho = 0.3;         // [m]
  double max_delta_beta = deg(10.0);  // [rad]
  double min_overlap = 0.5;           // fraction of the extracted segment, (0, 1]
  double end_tolerance = 0.3;         // [m]
};

// Throws UsageError naming the first invalid option.
void validate(const LineMatchOptions& o);

struct LineToMapMatches {
  std::vector<locbench::laser::SegmentMatch> matches;  // ordered by map segment
  std::vector<std::optional<std::size_t>> segment_of;  // per extracted line: its map segment
  std::size_t work = 0;
};

// `lines` must have been fitted in the world frame.
LineToMapMatches match_lines_to_map(std::span<const ExtractedLine> lines, const LineMap& map,
                                    const Eigen::Vector2d& pivot, const LineMatchOptions& options = {});

}  // namespace locbench::baselines::laser
