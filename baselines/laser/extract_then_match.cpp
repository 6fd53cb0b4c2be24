#include "baselines/laser/extract_then_match.h"

#include <utility>

namespace locbench::laser {
namespace {

// Scan under the estimate → world-frame lines (by `extract`) → map matches.
template <class Extract>
MatchResult extract_then_match(const Scan& scan, const LineMap& map, const Pose2& estimate,
                               const LineMatchOptions& matching, Extract extract) {
  const std::vector<ScanPoint> points = scan_points(scan, estimate);  // eq. 5.2–5.3
  ExtractionResult extracted = extract(points, LineFrame::world);
  const Eigen::Vector2d pivot = (estimate * scan.sensor_pose).translation();
  LineToMapMatches m = match_lines_to_map(extracted.lines, map, pivot, matching);
  MatchResult result;
  result.matches = std::move(m.matches);
  result.work = extracted.work + m.work;
  return result;
}

}  // namespace

SplitAndMergeMatcher::SplitAndMergeMatcher(const SplitAndMergeMatcherOptions& options)
    : options_(options) {
  validate(options_.extraction);
  validate(options_.matching);
}

MatchResult SplitAndMergeMatcher::match(const Scan& scan, const LineMap& map,
                                        const Pose2& estimate) const {
  return extract_then_match(scan, map, estimate, options_.matching,
                            [this](std::span<const ScanPoint> p, LineFrame f) {
                              return split_and_merge(p, f, options_.extraction);
                            });
}

ExtractionResult SplitAndMergeMatcher::extract_lines(const Scan& scan) const {
  return split_and_merge(scan_points(scan, Pose2()), LineFrame::robot, options_.extraction);
}

AgglomerativeMatcher::AgglomerativeMatcher(const AgglomerativeMatcherOptions& options)
    : options_(options) {
  validate(options_.extraction);
  validate(options_.matching);
}

MatchResult AgglomerativeMatcher::match(const Scan& scan, const LineMap& map,
                                        const Pose2& estimate) const {
  return extract_then_match(scan, map, estimate, options_.matching,
                            [this](std::span<const ScanPoint> p, LineFrame f) {
                              return agglomerative_lines(p, f, options_.extraction);
                            });
}

ExtractionResult AgglomerativeMatcher::extract_lines(const Scan& scan) const {
  return agglomerative_lines(scan_points(scan, Pose2()), LineFrame::robot, options_.extraction);
}

RwhtMatcher::RwhtMatcher(const RwhtMatcherOptions& options) : options_(options) {
  validate(options_.extraction);
  validate(options_.matching);
}

MatchResult RwhtMatcher::match(const Scan& scan, const LineMap& map,
                               const Pose2& estimate) const {
  return extract_then_match(scan, map, estimate, options_.matching,
                            [this](std::span<const ScanPoint> p, LineFrame f) {
                              return rwht_lines(p, f, options_.extraction).extraction;
                            });
}

ExtractionResult RwhtMatcher::extract_lines(const Scan& scan) const {
  return rwht_lines(scan_points(scan, Pose2()), LineFrame::robot, options_.extraction).extraction;
}

}  // namespace locbench::laser
