#include "baselines/laser/extract_then_match.h"

#include <utility>

namespace locbench::baselines::laser {
using locbench::laser::MatchResult, locbench::laser::scan_points, locbench::laser::ScanPoint;
namespace {

// Each baseline's name and extraction step (lines in frame `f`).
const char* name_of(const SplitAndMergeOptions&) { return "split_and_merge"; }
const char* name_of(const AgglomerativeOptions&) { return "agglomerative"; }
const char* name_of(const RwhtOptions&) { return "rwht"; }

ExtractionResult lines_of(std::span<const ScanPoint> p, LineFrame f, const SplitAndMergeOptions& o) {
  return split_and_merge(p, f, o);
}
ExtractionResult lines_of(std::span<const ScanPoint> p, LineFrame f, const AgglomerativeOptions& o) {
  return agglomerative_lines(p, f, o);
}
ExtractionResult lines_of(std::span<const ScanPoint> p, LineFrame f, const RwhtOptions& o) {
  return rwht_lines(p, f, o).extraction;
}

}  // namespace

template <class Extraction>
ExtractThenMatcher<Extraction>::ExtractThenMatcher(const Options& options) : options_(options) {
  validate(options_.extraction);
  validate(options_.matching);
}

// Scan under the estimate → world-frame lines → map matches.
template <class Extraction>
MatchResult ExtractThenMatcher<Extraction>::match(const Scan& scan, const LineMap& map, const Pose2& estimate) const {
  const std::vector<ScanPoint> points = scan_points(scan, estimate);  // eq. 5.2–5.3
  ExtractionResult extracted = lines_of(points, LineFrame::world, options_.extraction);
  const Eigen::Vector2d pivot = (estimate * scan.sensor_pose).translation();
  LineToMapMatches m = match_lines_to_map(extracted.lines, map, pivot, options_.matching);
  MatchResult result;
  result.matches = std::move(m.matches);
  result.work = extracted.work + m.work;
  return result;
}

template <class Extraction>
ExtractionResult ExtractThenMatcher<Extraction>::extract_lines(const Scan& scan) const {
  return lines_of(scan_points(scan, Pose2()), LineFrame::robot, options_.extraction);
}

template <class Extraction>
std::string ExtractThenMatcher<Extraction>::name() const {
  return name_of(options_.extraction);
}

template class ExtractThenMatcher<SplitAndMergeOptions>;
template class ExtractThenMatcher<AgglomerativeOptions>;
template class ExtractThenMatcher<RwhtOptions>;

}  // namespace locbench::baselines::laser
