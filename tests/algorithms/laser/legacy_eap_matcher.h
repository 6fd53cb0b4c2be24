#pragma once
// The EAP matcher as it was before it was made faster (its EapMatcher::match verbatim; the
// commit is named in docs/decisions.md): regions as EapRegion objects, nearest-segment ownership by contains() and a
// square root per point–segment pair, fit_line per run. Kept only as the reference of the equivalence test
// (eap_equivalence_test.cpp): the new EapMatcher must give the same matches.
#include <memory>
#include <string>

#include "algorithms/laser/eap_matcher.h"

namespace locbench::laser::legacy {

class LegacyEapMatcher : public SegmentMatcher {
 public:
  explicit LegacyEapMatcher(EapOptions options = {}) : options_(options) { validate(options_); }
  LegacyEapMatcher(std::shared_ptr<const SegmentGridIndex> index, EapOptions options = {})
      : options_(options), index_(std::move(index)) {
    validate(options_);
  }
  std::string name() const override { return index_ ? "legacy_eap_indexed" : "legacy_eap"; }
  MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;

 private:
  EapOptions options_;
  std::shared_ptr<const SegmentGridIndex> index_;
};

}  // namespace locbench::laser::legacy
