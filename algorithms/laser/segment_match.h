#pragma once
// What every scan-to-map matcher returns (EAP, g-weighted Hough, and the extract-then-match
// baselines): for each map segment it recognised, the scan points it assigned to it and the
// line fitted to them. Chapter 6's pose correction consumes this.
#include <cstddef>
#include <string>
#include <vector>

#include "algorithms/laser/line_fit.h"
#include "algorithms/laser/scan_points.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::laser {

struct SegmentMatch {
  std::size_t map_segment = 0;    // index into LineMap::segments
  std::vector<ScanPoint> points;  // the assigned points, in beam order
  LineFit fit;                    // least-squares line of points[i].world
};

struct MatchResult {
  std::vector<SegmentMatch> matches;
  // Inner-loop work done, for complexity plots: point–segment membership tests for the
  // map-driven matchers, point–point or point–line tests for the extract-then-match pipelines.
  std::size_t work = 0;
};

// A scan + a map + a pose estimate → matched segments. Implementations are stateless apart
// from their options, so one instance can be shared across threads.
class SegmentMatcher {
 public:
  virtual ~SegmentMatcher() = default;
  virtual std::string name() const = 0;  // stable, e.g. "eap", "split_and_merge"
  virtual MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const = 0;
};

}  // namespace locbench::laser
