#pragma once
// The input checks every pose-correction entry point makes, stated once so that each names
// itself (`who`) in the same words.
#include <cmath>
#include <string>

#include "algorithms/laser/segment_match.h"
#include "core/errors.h"
#include "core/line_map.h"
#include "core/pose2.h"

namespace locbench::pose_correction {

// Throws UsageError "<who>: the estimate is not finite".
inline void require_finite_estimate(const Pose2& estimate, const char* who) {
  if (!std::isfinite(estimate.x) || !std::isfinite(estimate.y) || !std::isfinite(estimate.theta)) {
    throw UsageError(std::string(who) + ": the estimate is not finite");
  }
}

// A correction's result before any correction: the estimate (checked as above) as `corrected`.
template <class Correction>
Correction uncorrected(const Pose2& estimate, const char* who) {
  require_finite_estimate(estimate, who);
  Correction out;
  out.corrected = estimate;
  return out;
}

// The map segment a match names; throws UsageError "<who>: a match names map segment k, the
// map has n" when there is no such segment.
inline const Segment& matched_segment(const laser::SegmentMatch& m, const LineMap& map, const char* who) {
  if (m.map_segment >= map.segments.size()) {
    throw UsageError(std::string(who) + ": a match names map segment " + std::to_string(m.map_segment) +
                     ", the map has " + std::to_string(map.segments.size()));
  }
  return map.segments[m.map_segment];
}

}  // namespace locbench::pose_correction
