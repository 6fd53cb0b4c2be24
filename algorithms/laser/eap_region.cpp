#include "algorithms/laser/eap_region.h"

#include "core/enum_names.h"
#include "core/errors.h"

namespace locbench::laser {

// Why ω1 = ω2 \ ω3 is the stadium (checked numerically in eap_region_test.cpp). Let t be the
// position of p along P1→P2 (length L) and h its distance from the line, |h| ≤ d in ω2.
//  • 0 ≤ t ≤ L: d1² = t² + h² ≤ L² + d² = d3² and likewise d2² ≤ d3², so p ∉ ω3: the whole
//    rectangle is kept, as in the stadium.
//  • t > L (beyond P2; t < 0 is symmetric): d1 > d2, so p ∈ ω1 ⇔ d2 ≤ d or d1 ≤ d3. If d1 ≤ d3
//    and d2 > d then t² + h² ≤ L² + d² < L² + (t − L)² + h², i.e. 2tL < 2L², t < L: impossible.
//    So beyond P2, p ∈ ω1 ⇔ d2 ≤ d — the end disc of the stadium.
// Hence ω1 equals {p : dist(p, P1P2) ≤ d} with the same ≤ on every boundary.

constexpr EnumNames<RegionRule, 2> kRegionRules{{{RegionRule::kThesis, "thesis"}, {RegionRule::kStadium, "stadium"}}};

const char* to_string(RegionRule r) { return enum_name(kRegionRules, r); }
RegionRule region_rule_from_string(const std::string& s) { return enum_value(kRegionRules, s, "region rule must be"); }

EapRegion::EapRegion(const Segment& segment, double d_limit) : p1_(segment.p1), p2_(segment.p2), d_limit_(d_limit) {
  if (!(std::isfinite(d_limit) && d_limit > 0.0)) {
    throw UsageError("EapRegion: d_limit must be finite and > 0");
  }
  const Eigen::Vector2d d = p2_ - p1_;
  length_ = d.norm();
  if (!(std::isfinite(length_) && length_ > 0.0)) {
    throw UsageError("EapRegion: segment must have finite, non-zero length");
  }
  direction_ = d / length_;
  normal_ = {-direction_.y(), direction_.x()};
  d_limit_squared_ = d_limit * d_limit;
  d3_squared_ = d_limit_squared_ + d.squaredNorm();  // (5.14), squared
}

}  // namespace locbench::laser
