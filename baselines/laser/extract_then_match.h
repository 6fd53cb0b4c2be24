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

namespace locbench::laser {

struct SplitAndMergeMatcherOptions {
  SplitAndMergeOptions extraction;
  LineMatchOptions matching;
};

struct AgglomerativeMatcherOptions {
  AgglomerativeOptions extraction;
  LineMatchOptions matching;
};

struct RwhtMatcherOptions {
  RwhtOptions extraction;
  LineMatchOptions matching;
};

// Each constructor throws UsageError for invalid options.
class SplitAndMergeMatcher final : public SegmentMatcher {
 public:
  explicit SplitAndMergeMatcher(const SplitAndMergeMatcherOptions& options = {});
  std::string name() const override { return "split_and_merge"; }
  MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;
  ExtractionResult extract_lines(const Scan& scan) const;
  const SplitAndMergeMatcherOptions& options() const { return options_; }

 private:
  SplitAndMergeMatcherOptions options_;
};

class AgglomerativeMatcher final : public SegmentMatcher {
 public:
  explicit AgglomerativeMatcher(const AgglomerativeMatcherOptions& options = {});
  std::string name() const override { return "agglomerative"; }
  MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;
  ExtractionResult extract_lines(const Scan& scan) const;
  const AgglomerativeMatcherOptions& options() const { return options_; }

 private:
  AgglomerativeMatcherOptions options_;
};

class RwhtMatcher final : public SegmentMatcher {
 public:
  explicit RwhtMatcher(const RwhtMatcherOptions& options = {});
  std::string name() const override { return "rwht"; }
  MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;
  ExtractionResult extract_lines(const Scan& scan) const;
  const RwhtMatcherOptions& options() const { return options_; }

 private:
  RwhtMatcherOptions options_;
};

}  // namespace locbench::laser
