#pragma once
// The Effective Area of Plane matcher (§5.3): scan points are matched to map segments directly,
// without clustering. Per map segment P1P2, with the scan points in the world frame under the
// pose estimate (5.3):
//  1. membership: the points inside ω1 (5.12–5.17, eap_region.h);
//  2. runs: maximal sequences of those points that are consecutive in the scan (below);
//  3. acceptance of a run: its g-weighted score Σ g (5.6 with w = 1 inside ω1, hough_weighted.h)
//     ≥ c_limit — with the thesis's g ≡ 1 (5.11), at least c_limit = 5 points — and the
//     distance between its first and last point > min_extent (200 mm); and (ours, optional)
//     the chord from its first to its last point within max_direction_error of the segment;
//  4. the accepted runs of a segment become one SegmentMatch: their points in beam order and
//     the least-squares line through all of them (fit_line).
// "Consecutive in the scan" (the thesis's condition 2), precisely: two member points are
// consecutive when no *valid* scan point lies between them in beam order, apart from points
// already removed (claimed, below). Invalid beams (no return, Scan::valid false) carry no
// point: they neither break nor extend a run, so a wall seen across a drop-out is one run.
// A valid point between them that is outside ω1, or owned by another segment, breaks the run.
//
// Claiming (remove_claimed = true; the thesis deletes matched points, §5.3): each point goes
// to at most one segment, decided deterministically by `claim_order`:
//  - kNearestSegment (default, ours): a point inside several ω1 belongs to the segment nearest
//    to it (distance to the closed segment; ties → lower map index), before runs are formed.
//    Corner points then go to the wall they lie on, which keeps the fits unbiased.
//  - kMapOrder (the thesis's loop): segments are processed in map order; each one tests the
//    points not yet claimed, and the points of its accepted runs are deleted for the later
//    segments. A segment processed early swallows the other wall's points within d_limit of a
//    shared corner, biasing its fit (measured in the README). `work` here is comparable with
//    the thesis's "1093 loop iterations".
// With remove_claimed = false a point may be matched to every segment whose ω1 holds it.
//
// Indexed mode (beyond the thesis): built with a SegmentGridIndex, the matcher tests each point
// only against the segments listed in its grid cell, so the cost no longer grows with the map;
// the matches are identical to the plain matcher's. The map passed to match() must be the
// index's map: pass index->map() (checked in O(1)); another LineMap object is compared segment
// by segment (O(m)) and rejected with UsageError when it differs.
//
// `work` counts ω1 membership tests.
//
// Implementation (the same matches as the plain one, shown by eap_equivalence_test): segments in
// flat arrays (eap_matcher_segments.h) tested band first, branch-free, with the end caps and
// the nearest-segment comparison on squared distances only; one pass of moments per run
// (eap_matcher_moments.h) shared by the direction check, the fit and the trim; cos/sin of the
// bearings cached per scan geometry and all buffers reused across calls, per thread (so one
// matcher can still be shared across threads).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "algorithms/laser/eap_region.h"
#include "algorithms/laser/hough_weighted.h"
#include "algorithms/laser/segment_grid_index.h"
#include "algorithms/laser/segment_match.h"

namespace locbench::laser {
namespace detail {
class EapSegmentTable;
}

enum class ClaimOrder { kNearestSegment, kMapOrder };
const char* to_string(ClaimOrder c);
// "nearest_segment" | "map_order"; throws UsageError otherwise.
ClaimOrder claim_order_from_string(const std::string& s);

struct EapOptions {
  double d_limit = 0.200;     // [m] half-width of ω2 (5.5); §5.3, chosen in §6.4
  double c_limit = 5.0;       // minimum score Σg of a run; with g ≡ 1 a point count (§5.3: 5)
  double min_extent = 0.200;  // [m] a run's first-to-last distance must exceed this (§5.3)
  // Ours, not the thesis's (0 = off, the thesis's rule): the chord from a run's first to its last
  // point must lie within this angle of the segment's direction [rad]. Without it, five points
  // of a perpendicular wall inside a short segment's ω1 are accepted as that segment (block C's
  // right face from the thesis pose under a 3° heading error), and chapter 6 turns them into a
  // Δθ of −87° (laser/table_6_2 reports both settings).
  double max_direction_error = 0.5235987755982988;  // 30°
  // Ours (0 = off, the thesis): after the fit, the point farthest from the line is dropped and
  // the line refitted while that distance exceeds this [m] (10σ of the LMS 200); a match left
  // with fewer than c_limit points is dropped. Removes an adjacent wall's points that a pose
  // error carries into the end-cap band (Tables 6.3/6.4 estimates 2 and 6).
  double trim_distance = 0.05;
  HoughWeight weighting;       // g of 5.8/5.10/5.11; default g ≡ 1 as in the thesis
  bool remove_claimed = true;  // §5.3: delete matched points
  ClaimOrder claim_order = ClaimOrder::kNearestSegment;
  RegionRule region = RegionRule::kThesis;  // ω1 as published (equal to the stadium)
};
// Throws UsageError naming the first invalid field.
void validate(const EapOptions& o);
void to_json(nlohmann::json& j, const EapOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, EapOptions& o);
// The Markdown table of the options (key, default, unit, allowed, meaning), as in README.md.
std::string eap_options_table();

class EapMatcher : public SegmentMatcher {
 public:
  // Plain: every point is tested against every segment, O(n·m).
  explicit EapMatcher(EapOptions options = {});
  // Indexed: throws UsageError for a null index or index->d_limit() ≠ options.d_limit.
  EapMatcher(std::shared_ptr<const SegmentGridIndex> index, EapOptions options = {});

  std::string name() const override { return index_ ? "eap_indexed" : "eap"; }
  // Throws UsageError for a non-finite estimate, a scan whose bearings and ranges differ in
  // length, a zero-length map segment (plain) or a map that is not the index's (indexed).
  MatchResult match(const Scan& scan, const LineMap& map, const Pose2& estimate) const override;

  const EapOptions& options() const { return options_; }
  const SegmentGridIndex* index() const { return index_.get(); }

 private:
  EapOptions options_;
  std::shared_ptr<const SegmentGridIndex> index_;
  std::shared_ptr<const detail::EapSegmentTable> table_;  // index_'s segments, flat (indexed)
};

}  // namespace locbench::laser
