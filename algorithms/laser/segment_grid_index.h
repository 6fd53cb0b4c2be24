#pragma once
// Beyond the thesis: a uniform grid over a LineMap in which each cell lists the segments whose
// d_limit-inflated region (the stadium of radius d_limit about the segment, which contains ω1,
// see eap_region.h) overlaps the cell. Built once per map in O(m · cells per segment); a
// lookup is O(1), so an EAP matcher using it tests each scan point only against the segments
// near it and its cost stays nearly flat as the map grows (eap_matcher.h).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algorithms/laser/eap_region.h"
#include "core/line_map.h"

namespace locbench::laser {

struct GridIndexOptions {
  double d_limit = 0.200;  // [m] inflation; must equal the matcher's EapOptions::d_limit
  // [m] cell side; 0 = automatic: max(2·d_limit, √(bounding-box area / (16·m))), i.e. about
  // 16 cells per segment, never finer than the band width.
  double cell_size = 0.0;
};
void validate(const GridIndexOptions& o);

class SegmentGridIndex {
 public:
  // Keeps its own copy of the map. Throws UsageError for an empty map, a zero-length or
  // non-finite segment, bad options, or a grid of more than 2^24 cells (choose a larger cell).
  explicit SegmentGridIndex(LineMap map, GridIndexOptions options = {});

  const LineMap& map() const { return map_; }
  // ω1 of every segment with the index's d_limit, in map order.
  const std::vector<EapRegion>& regions() const { return regions_; }
  double d_limit() const { return options_.d_limit; }
  double cell_size() const { return cell_; }
  std::size_t columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  // Σ over cells of their list lengths (memory and build cost).
  std::size_t entries() const { return cell_segments_.size(); }

  // The segments listed in p's cell, ascending; empty outside the grid (no segment's inflated
  // region reaches there) or for a non-finite p. Every segment whose ω1 contains p is listed.
  std::span<const std::uint32_t> candidates(const Eigen::Vector2d& p) const {
    const double fx = (p.x() - origin_.x()) * inv_cell_;
    const double fy = (p.y() - origin_.y()) * inv_cell_;
    // Written so that NaN fails too.
    if (!(fx >= 0.0 && fy >= 0.0 && fx < columns_f_ && fy < rows_f_)) return {};
    const std::size_t cell = static_cast<std::size_t>(fy) * columns_ + static_cast<std::size_t>(fx);
    return {cell_segments_.data() + cell_start_[cell], cell_start_[cell + 1] - cell_start_[cell]};
  }

 private:
  LineMap map_;
  GridIndexOptions options_;
  std::vector<EapRegion> regions_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // lower-left corner of the grid
  double cell_ = 0.0;
  double inv_cell_ = 0.0;
  std::size_t columns_ = 0, rows_ = 0;
  double columns_f_ = 0.0, rows_f_ = 0.0;
  // CSR: cell c lists cell_segments_[cell_start_[c], cell_start_[c + 1]).
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> cell_segments_;
};

// Euclidean distance between the closed segment ab and the axis-aligned box [lo, hi]; 0 when
// they touch or cross.
double segment_box_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                            const Eigen::Vector2d& hi);

}  // namespace locbench::laser
