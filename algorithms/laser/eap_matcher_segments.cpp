#include "algorithms/laser/eap_matcher_segments.h"

#include <string>

#include "core/errors.h"

namespace locbench::laser::detail {

void EapSegmentTable::assign(std::span<const EapRegion> regions) {
  const std::size_t m = regions.size();
  for (auto* v : {&ax_, &ay_, &nx_, &ny_, &bx_, &by_, &dx_, &dy_, &length_, &d3_squared_, &mx_, &my_}) {
    v->resize(m);
  }
  source_.resize(m);
  d_limit_ = m > 0 ? regions.front().d_limit() : 0.0;
  d_limit_squared_ = d_limit_ * d_limit_;  // as EapRegion computes it
  for (std::size_t j = 0; j < m; ++j) {
    const EapRegion& r = regions[j];
    ax_[j] = r.p1().x();
    ay_[j] = r.p1().y();
    nx_[j] = r.normal().x();
    ny_[j] = r.normal().y();
    bx_[j] = r.p2().x();
    by_[j] = r.p2().y();
    dx_[j] = r.direction().x();
    dy_[j] = r.direction().y();
    length_[j] = r.length();
    d3_squared_[j] = r.d3_squared();
    mx_[j] = 0.5 * (r.p1().x() + r.p2().x());
    my_[j] = 0.5 * (r.p1().y() + r.p2().y());
    source_[j] = {r.p1(), r.p2()};
  }
}

void EapSegmentTable::assign(const LineMap& map, double d_limit) {
  std::vector<EapRegion> regions;
  regions.reserve(map.segments.size());
  for (std::size_t j = 0; j < map.segments.size(); ++j) {
    try {
      regions.emplace_back(map.segments[j], d_limit);
    } catch (const UsageError& e) {
      throw UsageError("map segment " + std::to_string(j) + ": " + e.what());
    }
  }
  assign(regions);
  d_limit_ = d_limit;
  d_limit_squared_ = d_limit * d_limit;
}

bool EapSegmentTable::built_from(const LineMap& map, double d_limit) const {
  if (map.segments.size() != source_.size() || d_limit != d_limit_) return false;
  for (std::size_t j = 0; j < source_.size(); ++j) {
    if (map.segments[j].p1 != source_[j].p1 || map.segments[j].p2 != source_[j].p2) return false;
  }
  return true;
}

}  // namespace locbench::laser::detail
