#pragma once
// The extract-then-match baselines as SegmentMatchers, beside the thesis's EAP and g-weighted
// Hough matchers: match(scan, map, estimate) = scan_points under the estimate (eq. 5.2–5.3) →
// extract lines in the world frame → match them to the map (line_to_map_matching.h), the Δρ
// pivot being the estimated sensor position. MatchResult::work adds the extractor's work and
// the line–segment tests. extract_lines(scan) is the map-free half, in the robot frame, for
// real logs that come without a map.
#include <string>

#include "algorithms/laser/segment_match.h"
#include "baselines/laser/agglomerative_lines.h"
#include "baselines/laser/line_to_map_matching.h"
#include "baselines/laser/rwht.h"
#include "baselines/laser/split_and_merge.h"

namespace locbench::baselines::laser {

// A baseline's options: its extractor's (SplitAndMergeOptions, AgglomerativeOptions or
// RwhtOptions) and the line-to-map matching's.
template <class Extraction>
struct ExtractThenMatchOptions {
  Extraction extraction;
  LineMatchOptions matching;
};
using SplitAndMergeMatcherOptions = ExtractThenMatchOptions<SplitAndMergeOptions>;
using AgglomerativeMatcherOptions = ExtractThenMatchOptions<AgglomerativeOptions>;
using RwhtMatcherOptions = ExtractThenMatchOptions<RwhtOptions>;

// One matcher per extractor; the three differ only in the extraction step (and their name).
template <class Extraction>
class ExtractThenMatcher final : public locbench::laser::SegmentMatcher {
 public:
  using Options = ExtractThenMatchOptions<Extraction>;
  // Throws UsageError for invalid options.
  explicit ExtractThenMatcher(const Options& options = {});
  std::string name() const override;
  locbench::laser::MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;
  ExtractionResult extract_lines(const Scan& scan) const;
  const Options& options() const { return options_; }

 private:
  Options options_;
};
using SplitAndMergeMatcher = ExtractThenMatcher<SplitAndMergeOptions>;  // "split_and_merge"
using AgglomerativeMatcher = ExtractThenMatcher<AgglomerativeOptions>;  // "agglomerative"
using RwhtMatcher = ExtractThenMatcher<RwhtOptions>;                    // "rwht"
extern template class ExtractThenMatcher<SplitAndMergeOptions>;
extern template class ExtractThenMatcher<AgglomerativeOptions>;
extern template class ExtractThenMatcher<RwhtOptions>;

}  // namespace locbench::baselines::laser
