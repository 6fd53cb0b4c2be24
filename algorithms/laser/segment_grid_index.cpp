#include "algorithms/laser/segment_grid_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"

namespace locbench::laser {
namespace {

constexpr std::size_t kMaxCells = std::size_t{1} << 24;

double point_box_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double dx = std::max({lo.x() - p.x(), 0.0, p.x() - hi.x()});
  const double dy = std::max({lo.y() - p.y(), 0.0, p.y() - hi.y()});
  return std::hypot(dx, dy);
}

// Liang–Barsky: does the segment a + t(b − a), t ∈ [0, 1], meet the box?
bool segment_meets_box(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                       const Eigen::Vector2d& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

double segment_box_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                            const Eigen::Vector2d& hi) {
  if (segment_meets_box(a, b, lo, hi)) return 0.0;
  // Disjoint convex sets: the closest pair has an end point of the segment or a box corner.
  const Segment s{a, b};
  double d = std::min(point_box_distance(a, lo, hi), point_box_distance(b, lo, hi));
  for (const Eigen::Vector2d& c : {lo, hi, Eigen::Vector2d(lo.x(), hi.y()), Eigen::Vector2d(hi.x(), lo.y())}) {
    d = std::min(d, distance_to_segment(s, c));
  }
  return d;
}

void validate(const GridIndexOptions& o) {
  if (!(std::isfinite(o.d_limit) && o.d_limit > 0.0)) {
    throw UsageError("GridIndexOptions.d_limit must be finite and > 0");
  }
  if (!(std::isfinite(o.cell_size) && o.cell_size >= 0.0)) {
    throw UsageError("GridIndexOptions.cell_size must be finite and ≥ 0 (0 = automatic)");
  }
}

SegmentGridIndex::SegmentGridIndex(LineMap map, GridIndexOptions options) : map_(std::move(map)), options_(options) {
  validate(options_);
  const std::size_t m = map_.segments.size();
  if (m == 0) throw UsageError("SegmentGridIndex: the map has no segments");
  if (m > std::numeric_limits<std::uint32_t>::max()) {
    throw UsageError("SegmentGridIndex: more than 2^32 − 1 segments");
  }
  regions_.reserve(m);
  Eigen::Vector2d lo = map_.segments.front().p1, hi = lo;
  for (std::size_t j = 0; j < m; ++j) {
    const Segment& s = map_.segments[j];
    try {
      regions_.emplace_back(s, options_.d_limit);
    } catch (const UsageError& e) {
      throw UsageError("SegmentGridIndex: segment " + std::to_string(j) + ": " + e.what());
    }
    lo = lo.cwiseMin(s.p1).cwiseMin(s.p2);
    hi = hi.cwiseMax(s.p1).cwiseMax(s.p2);
  }
  // Inflation with a margin for rounding, so that every point a membership test accepts
  // (computed in floating point) falls in a cell that lists the segment.
  const double extent = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  const double r = options_.d_limit * (1.0 + 1e-9) + 1e-9 * (1.0 + extent);
  lo.array() -= r;
  hi.array() += r;
  const Eigen::Vector2d size = hi - lo;
  const double area = size.x() * size.y();
  cell_ = options_.cell_size;
  if (cell_ == 0.0) {
    cell_ = std::max({2.0 * options_.d_limit, std::sqrt(area / (16.0 * static_cast<double>(m))),
                      std::sqrt(area / static_cast<double>(kMaxCells / 2))});
  }
  const double cols = std::max(1.0, std::ceil(size.x() / cell_));
  const double rows = std::max(1.0, std::ceil(size.y() / cell_));
  if (cols * rows > static_cast<double>(kMaxCells)) {
    throw UsageError("SegmentGridIndex: cell_size " + std::to_string(cell_) + " m gives " +
                     std::to_string(cols * rows) + " cells (more than 2^24); choose a larger one");
  }
  origin_ = lo;
  inv_cell_ = 1.0 / cell_;
  columns_ = static_cast<std::size_t>(cols);
  rows_ = static_cast<std::size_t>(rows);
  columns_f_ = cols;
  rows_f_ = rows;

  // (cell, segment) pairs, segments ascending, then a counting sort into CSR (stable, so each
  // cell's list stays ascending).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  pairs.reserve(4 * m);
  const auto cell_of = [&](double v, double o, std::size_t n) {
    const double f = std::floor((v - o) * inv_cell_);
    return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(n - 1)));
  };
  for (std::size_t j = 0; j < m; ++j) {
    const Segment& s = map_.segments[j];
    const Eigen::Vector2d blo = s.p1.cwiseMin(s.p2).array() - r;
    const Eigen::Vector2d bhi = s.p1.cwiseMax(s.p2).array() + r;
    const std::size_t x0 = cell_of(blo.x(), origin_.x(), columns_);
    const std::size_t x1 = cell_of(bhi.x(), origin_.x(), columns_);
    const std::size_t y0 = cell_of(blo.y(), origin_.y(), rows_);
    const std::size_t y1 = cell_of(bhi.y(), origin_.y(), rows_);
    for (std::size_t cy = y0; cy <= y1; ++cy) {
      for (std::size_t cx = x0; cx <= x1; ++cx) {
        const Eigen::Vector2d clo = origin_ + cell_ * Eigen::Vector2d(static_cast<double>(cx), static_cast<double>(cy));
        const Eigen::Vector2d chi = clo + Eigen::Vector2d(cell_, cell_);
        if (segment_box_distance(s.p1, s.p2, clo, chi) <= r) {
          pairs.emplace_back(static_cast<std::uint32_t>(cy * columns_ + cx), static_cast<std::uint32_t>(j));
        }
      }
    }
  }
  if (pairs.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw UsageError("SegmentGridIndex: more than 2^32 − 1 cell entries; choose a larger cell");
  }
  const std::size_t cells = columns_ * rows_;
  cell_start_.assign(cells + 1, 0);
  for (const auto& [c, j] : pairs) ++cell_start_[c + 1];
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_segments_.resize(pairs.size());
  std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (const auto& [c, j] : pairs) cell_segments_[next[c]++] = j;
}

}  // namespace locbench::laser
