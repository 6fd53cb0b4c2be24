#pragma once
// Steps of the EAP matcher that do not depend on how it is made fast (the legacy reference in
// tests/ shares them): the input checks, the (point, segment) hits grouped by segment,
// consecutive points of a run, and the check that an index was built for the map being matched.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::laser::detail {

// UsageError unless the estimate is finite and the scan has a bearing for every range.
inline void require_matchable(const Scan& scan, const Pose2& estimate) {
  if (!(std::isfinite(estimate.x) && std::isfinite(estimate.y) && std::isfinite(estimate.theta))) {
    throw UsageError("EapMatcher: the pose estimate is not finite");
  }
  if (scan.bearings.size() != scan.ranges.size()) {
    throw UsageError("EapMatcher: the scan has " + std::to_string(scan.ranges.size()) + " ranges but " +
                     std::to_string(scan.bearings.size()) + " bearings");
  }
}

struct Hit {
  std::uint32_t segment;
  std::uint32_t point;  // index into the scan's valid points
  bool operator<(const Hit& o) const { return segment != o.segment ? segment < o.segment : point < o.point; }
};

// Calls f(segment, points) for each segment with hits, ascending; `hits` sorted.
template <class F>
void for_each_group(std::span<const Hit> hits, std::vector<std::uint32_t>& points, F&& f) {
  std::size_t k = 0;
  while (k < hits.size()) {
    const std::uint32_t segment = hits[k].segment;
    points.clear();
    for (; k < hits.size() && hits[k].segment == segment; ++k) points.push_back(hits[k].point);
    f(segment, std::span<const std::uint32_t>(points));
  }
}

// Points a < b of one segment are consecutive when no point between them is left (`deleted`
// null: nothing deleted, so only adjacent points are).
inline bool consecutive(std::uint32_t a, std::uint32_t b, const std::vector<char>* deleted) {
  if (b == a + 1) return true;
  if (deleted == nullptr) return false;
  for (std::uint32_t k = a + 1; k < b; ++k) {
    if ((*deleted)[k] == 0) return false;
  }
  return true;
}

// True when both maps have the same segments (endpoints equal) in the same order.
inline bool same_segments(const LineMap& a, const LineMap& b) {
  if (&a == &b) return true;
  if (a.segments.size() != b.segments.size()) return false;
  for (std::size_t j = 0; j < a.segments.size(); ++j) {
    if (a.segments[j].p1 != b.segments[j].p1 || a.segments[j].p2 != b.segments[j].p2) {
      return false;
    }
  }
  return true;
}

}  // namespace locbench::laser::detail
