#pragma once
// The map segments as the EAP matcher's inner loop reads them: flat arrays, one entry per
// segment, copied from each segment's EapRegion so that every value — and therefore every
// membership decision — is bit-for-bit the one EapRegion::contains computes.
//   band (5.5):      h = n·(p − P1), |h| ≤ d_limit       (n unit normal; same rounding as
//                    EapRegion, which is why P1 is stored rather than c = n·P1)
//   end caps:        ω1 = ω2 \ ω3 (5.12–5.17) or the stadium, on squared distances only
//   nearest segment: squared distance to the closed segment, no square root
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "algorithms/laser/eap_region.h"
#include "core/line_map.h"

namespace locbench::laser::detail {

class EapSegmentTable {
 public:
  // From regions built with one d_limit (at least one region, or an empty table).
  void assign(std::span<const EapRegion> regions);
  // Builds the regions of `map` (UsageError "map segment j: …" for a zero-length one).
  void assign(const LineMap& map, double d_limit);
  // True when this table was built from exactly these segments and d_limit.
  bool built_from(const LineMap& map, double d_limit) const;

  std::size_t size() const { return ax_.size(); }

  // The band test alone (5.5): |n·(p − P1)| ≤ d_limit; false for NaN.
  bool in_band(std::size_t j, double px, double py) const {
    const double h = nx_[j] * (px - ax_[j]) + ny_[j] * (py - ay_[j]);
    return std::abs(h) <= d_limit_;
  }
  // Bit j − first of the result: the band test of segment j, for j in [first, first + count),
  // count ≤ 64. Branch-free (two segments per SSE2 instruction where available, the same IEEE
  // operations as in_band), so the mostly failing tests cost no mispredictions. Used per point
  // where the points are visited one by one (no claims); band_masks is the batch form.
  std::uint64_t band_mask(std::size_t first, std::size_t count, double px, double py) const {
    std::uint64_t mask = 0;
    const double* ax = ax_.data() + first;
    const double* ay = ay_.data() + first;
    const double* nx = nx_.data() + first;
    const double* ny = ny_.data() + first;
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128d x = _mm_set1_pd(px), y = _mm_set1_pd(py), d = _mm_set1_pd(d_limit_);
    const __m128d sign = _mm_set1_pd(-0.0);
    for (; k + 2 <= count; k += 2) {
      const __m128d h = _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(nx + k), _mm_sub_pd(x, _mm_loadu_pd(ax + k))),
                                   _mm_mul_pd(_mm_loadu_pd(ny + k), _mm_sub_pd(y, _mm_loadu_pd(ay + k))));
      const __m128d inside = _mm_cmple_pd(_mm_andnot_pd(sign, h), d);  // |h| ≤ d, NaN false
      mask |= static_cast<std::uint64_t>(_mm_movemask_pd(inside)) << k;
    }
#endif
    for (; k < count; ++k) {
      const double h = nx[k] * (px - ax[k]) + ny[k] * (py - ay[k]);
      mask |= static_cast<std::uint64_t>(std::abs(h) <= d_limit_) << k;
    }
    return mask;
  }
  // For every point i < n: bit j − first of masks[i] |= the band test of segment j against
  // (px[i], py[i]), for j in [first, first + count), count ≤ 64. Segment-major, so the
  // segments' constants stay in registers while the points stream past (SSE2 where available:
  // two points per instruction, two segments per pass; the same IEEE operations as in_band).
  void band_masks(std::size_t first, std::size_t count, const double* px, const double* py, std::size_t n,
                  std::uint64_t* masks) const {
    std::size_t k = 0;
#if defined(__SSE2__)
    // Two segments per pass over the points: each pair of points is loaded once for both.
    const __m128d d = _mm_set1_pd(d_limit_), sign = _mm_set1_pd(-0.0);
    for (; k + 2 <= count; k += 2) {
      const std::size_t j = first + k;
      const __m128d ax0 = _mm_set1_pd(ax_[j]), ay0 = _mm_set1_pd(ay_[j]);
      const __m128d nx0 = _mm_set1_pd(nx_[j]), ny0 = _mm_set1_pd(ny_[j]);
      const __m128d ax1 = _mm_set1_pd(ax_[j + 1]), ay1 = _mm_set1_pd(ay_[j + 1]);
      const __m128d nx1 = _mm_set1_pd(nx_[j + 1]), ny1 = _mm_set1_pd(ny_[j + 1]);
      const __m128i bit0 = _mm_set1_epi64x(static_cast<long long>(std::uint64_t{1} << k));
      const __m128i bit1 = _mm_set1_epi64x(static_cast<long long>(std::uint64_t{2} << k));
      std::size_t i = 0;
      for (; i + 2 <= n; i += 2) {
        const __m128d x = _mm_loadu_pd(px + i), y = _mm_loadu_pd(py + i);
        const __m128d h0 = _mm_add_pd(_mm_mul_pd(nx0, _mm_sub_pd(x, ax0)), _mm_mul_pd(ny0, _mm_sub_pd(y, ay0)));
        const __m128d h1 = _mm_add_pd(_mm_mul_pd(nx1, _mm_sub_pd(x, ax1)), _mm_mul_pd(ny1, _mm_sub_pd(y, ay1)));
        const __m128i in0 = _mm_castpd_si128(_mm_cmple_pd(_mm_andnot_pd(sign, h0), d));
        const __m128i in1 = _mm_castpd_si128(_mm_cmple_pd(_mm_andnot_pd(sign, h1), d));
        auto* out = reinterpret_cast<__m128i*>(masks + i);
        _mm_storeu_si128(
            out, _mm_or_si128(_mm_loadu_si128(out), _mm_or_si128(_mm_and_si128(in0, bit0), _mm_and_si128(in1, bit1))));
      }
      for (; i < n; ++i) {
        if (in_band(j, px[i], py[i])) masks[i] |= std::uint64_t{1} << k;
        if (in_band(j + 1, px[i], py[i])) masks[i] |= std::uint64_t{2} << k;
      }
    }
#endif
    for (; k < count; ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        if (in_band(first + k, px[i], py[i])) masks[i] |= std::uint64_t{1} << k;
      }
    }
  }

  // For a point inside segment j's band: is it inside ω1 under `rule` (the rest of
  // EapRegion::contains)?
  bool in_caps(std::size_t j, double px, double py, RegionRule rule) const {
    const double qx = px - ax_[j], qy = py - ay_[j];
    const double rx = px - bx_[j], ry = py - by_[j];
    if (rule == RegionRule::kThesis) {
      const double d1s = qx * qx + qy * qy;  // d1² (5.12)
      const double d2s = rx * rx + ry * ry;  // d2² (5.13)
      return !(std::max(d1s, d2s) > d3_squared_[j] && std::min(d1s, d2s) > d_limit_squared_);
    }
    const double t = dx_[j] * qx + dy_[j] * qy;
    if (t < 0.0) return qx * qx + qy * qy <= d_limit_squared_;
    if (t > length_[j]) return rx * rx + ry * ry <= d_limit_squared_;
    return true;
  }
  bool contains(std::size_t j, double px, double py, RegionRule rule) const {
    return in_band(j, px, py) && in_caps(j, px, py, rule);
  }
  // Squared distance from p to the closed segment j; its square root is bit-equal to
  // EapRegion::distance_to_segment.
  double distance_squared(std::size_t j, double px, double py) const {
    const double qx = px - ax_[j], qy = py - ay_[j];
    const double t = std::clamp(dx_[j] * qx + dy_[j] * qy, 0.0, length_[j]);
    const double ex = qx - t * dx_[j], ey = qy - t * dy_[j];
    return ex * ex + ey * ey;
  }

  // Unit direction P1 → P2, and the midpoint (the origin of the matcher's moments: points of
  // ω1 lie within |P1P2|/2 + d_limit of it, which keeps one-pass moments accurate).
  double dx(std::size_t j) const { return dx_[j]; }
  double dy(std::size_t j) const { return dy_[j]; }
  double mid_x(std::size_t j) const { return mx_[j]; }
  double mid_y(std::size_t j) const { return my_[j]; }

 private:
  std::vector<double> ax_, ay_, nx_, ny_;  // P1 and the unit normal (band test)
  std::vector<double> bx_, by_;            // P2
  std::vector<double> dx_, dy_, length_;   // unit direction and |P1P2|
  std::vector<double> d3_squared_;         // d3² = d_limit² + |P1P2|² (5.14)
  std::vector<double> mx_, my_;            // midpoint
  double d_limit_ = 0.0, d_limit_squared_ = 0.0;
  std::vector<Segment> source_;  // the segments it was built from (built_from)
};

}  // namespace locbench::laser::detail
