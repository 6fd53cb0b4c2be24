#pragma once
// Scoring a scan-to-map match against the simulator's ground truth (which map segment each beam
// really hit): segment detection, line-parameter errors and point-assignment precision/recall.
// Shared by the laser experiments; internal to them.
#include <cstddef>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "datasets/sim/laser_model.h"

namespace locbench::experiments {

struct MatchScore {
  std::size_t detectable = 0;       // map segments hit by ≥ min_points beams spanning > min_extent
  std::size_t detected = 0;         // of those, matched with a majority of correct points
  std::size_t false_matches = 0;    // matched segments whose points are mostly not theirs
  std::vector<double> rho_errors;   // |Δρ| [m] of correct matches, line refitted in the true frame
  std::vector<double> beta_errors;  // |Δβ| [rad]
  std::size_t points_assigned = 0;
  std::size_t points_correct = 0;
  std::size_t points_on_map = 0;   // beams whose return is from a map segment
  double segment_recall() const;   // detected / detectable (1 when nothing was detectable)
  double point_precision() const;  // correct / assigned (1 when nothing was assigned)
  double point_recall() const;     // correct / on-map beams
};

// `labels[i]` is the world segment of beam i (LabelledScan::segment); indices ≥ map.segments
// .size() are clutter that is not in the map. `truth` is the robot's true pose.
MatchScore score_match(const laser::MatchResult& result, const LineMap& map, const std::vector<int>& labels,
                       const Scan& scan, const Pose2& truth, std::size_t min_points = 5, double min_extent = 0.2);

}  // namespace locbench::experiments
