#include "legacy_eap_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "algorithms/laser/eap_matcher_steps.h"
#include "core/errors.h"

namespace locbench::laser::legacy {
namespace {

using detail::consecutive;
using detail::for_each_group;
using detail::Hit;
using detail::same_segments;

constexpr std::uint32_t kNoSegment = static_cast<std::uint32_t>(-1);

// One match() call: the scan's points, the regions, the options and the output.
class MatchPass {
 public:
  MatchPass(const EapOptions& o, std::vector<ScanPoint> points, std::span<const EapRegion> regions, const LineMap& map,
            double sensor_heading)
      : o_(o), points_(std::move(points)), regions_(regions), map_(map), sensor_heading_(sensor_heading) {
    world_.reserve(points_.size());
    accepted_.reserve(points_.size());
  }

  std::size_t size() const { return points_.size(); }
  const Eigen::Vector2d& world(std::size_t i) const { return points_[i].world; }
  bool contains(std::uint32_t segment, std::size_t i) {
    ++result_.work;
    return regions_[segment].contains(points_[i].world, o_.region);
  }
  double distance(std::uint32_t segment, std::size_t i) const {
    return regions_[segment].distance_to_segment(points_[i].world);
  }

  // Forms the runs of `members` (ascending point indices, all inside ω1 of `segment`), accepts
  // them (§5.3 conditions 1–3) and appends one SegmentMatch holding every accepted run. Two
  // members are consecutive when every valid point between them is deleted (`deleted` may be
  // null: nothing deleted, so only adjacent points are consecutive). Accepted points are marked
  // in `deleted` when it is given.
  void accept_runs(std::uint32_t segment, std::span<const std::uint32_t> members, std::vector<char>* deleted) {
    accepted_.clear();
    std::size_t begin = 0;
    while (begin < members.size()) {
      std::size_t end = begin + 1;
      while (end < members.size() && consecutive(members[end - 1], members[end], deleted)) ++end;
      const std::span<const std::uint32_t> run = members.subspan(begin, end - begin);
      if (accepted(segment, run)) accepted_.insert(accepted_.end(), run.begin(), run.end());
      begin = end;
    }
    if (deleted != nullptr) {
      for (const std::uint32_t i : accepted_) (*deleted)[i] = 1;
    }
    emit(segment, accepted_);
  }

  // Nearest-segment claims: `owner[i]` is the segment point i belongs to (or kNoSegment). A run
  // is a maximal range of adjacent points with the same owner; the accepted ones are reported
  // per segment, segments ascending.
  void accept_owned_runs(std::span<const std::uint32_t> owner) {
    struct Run {
      std::uint32_t segment, begin, end;
      bool operator<(const Run& o) const { return segment != o.segment ? segment < o.segment : begin < o.begin; }
    };
    std::vector<Run> runs;
    std::uint32_t begin = 0;
    const auto n = static_cast<std::uint32_t>(owner.size());
    while (begin < n) {
      std::uint32_t end = begin + 1;
      while (end < n && owner[end] == owner[begin]) ++end;
      if (owner[begin] != kNoSegment) {
        accepted_.clear();
        for (std::uint32_t i = begin; i < end; ++i) accepted_.push_back(i);
        if (accepted(owner[begin], accepted_)) runs.push_back({owner[begin], begin, end});
      }
      begin = end;
    }
    std::sort(runs.begin(), runs.end());
    for (std::size_t k = 0; k < runs.size();) {
      const std::uint32_t segment = runs[k].segment;
      accepted_.clear();
      for (; k < runs.size() && runs[k].segment == segment; ++k) {
        for (std::uint32_t i = runs[k].begin; i < runs[k].end; ++i) accepted_.push_back(i);
      }
      emit(segment, accepted_);
    }
  }

  MatchResult take_result() { return std::move(result_); }

 private:
  // One SegmentMatch of `segment` with the points `indices` (ascending) and their line.
  void emit(std::uint32_t segment, std::span<const std::uint32_t> indices) {
    if (indices.empty()) return;
    SegmentMatch m;
    m.map_segment = segment;
    m.points.reserve(indices.size());
    world_.clear();
    for (const std::uint32_t i : indices) {
      m.points.push_back(points_[i]);
      world_.push_back(points_[i].world);
    }
    m.fit = fit_line(world_);
    // Ours: trim the farthest point from the fitted line while it is beyond trim_distance
    // (points of an adjacent wall inside the end-cap band under a pose error), refit each time.
    while (o_.trim_distance > 0.0 && !world_.empty()) {
      const Eigen::Vector2d n(std::cos(m.fit.line.beta), std::sin(m.fit.line.beta));
      std::size_t worst = 0;
      double worst_r = -1.0;
      for (std::size_t k = 0; k < world_.size(); ++k) {
        const double r = std::abs(n.dot(world_[k]) - m.fit.line.rho);
        if (r > worst_r) {
          worst_r = r;
          worst = k;
        }
      }
      if (worst_r <= o_.trim_distance) break;
      world_.erase(world_.begin() + static_cast<std::ptrdiff_t>(worst));
      m.points.erase(m.points.begin() + static_cast<std::ptrdiff_t>(worst));
      if (static_cast<double>(world_.size()) < std::max(2.0, o_.c_limit)) return;  // nothing left
      m.fit = fit_line(world_);
    }
    result_.matches.push_back(std::move(m));
  }

  // §5.3: score Σ g ≥ C_limit (5.6, w = 1 inside ω1; with g ≡ 1 the point count) and the first
  // and last point more than min_extent apart.
  bool accepted(std::uint32_t segment, std::span<const std::uint32_t> run) const {
    const Eigen::Vector2d& a = points_[run.front()].world;
    const Eigen::Vector2d& b = points_[run.back()].world;
    if (!((b - a).norm() > o_.min_extent)) return false;
    if (o_.max_direction_error > 0.0) {  // ours: the run's LS line must run along the segment
      run_world_.clear();
      for (const std::uint32_t i : run) run_world_.push_back(points_[i].world);
      const Eigen::Vector2d d = (map_.segments[segment].p2 - map_.segments[segment].p1).normalized();
      const Eigen::Vector2d f = fit_line(run_world_).direction;
      if (std::abs(d.x() * f.y() - d.y() * f.x()) > std::sin(o_.max_direction_error)) return false;
    }
    if (o_.weighting.kind == HoughWeighting::kCount) {
      return static_cast<double>(run.size()) >= o_.c_limit;  // (5.11)
    }
    const double beta = map_.segments[segment].line().beta;
    double score = 0.0;
    for (const std::uint32_t i : run) {
      score += hough_weight(points_[i], sensor_heading_, beta, o_.weighting);
    }
    return score >= o_.c_limit;
  }

  const EapOptions& o_;
  mutable std::vector<Eigen::Vector2d> run_world_;  // scratch of accepted()
  std::vector<ScanPoint> points_;
  std::span<const EapRegion> regions_;
  const LineMap& map_;
  double sensor_heading_;
  MatchResult result_;
  std::vector<std::uint32_t> accepted_;  // points of the current segment's accepted runs
  std::vector<Eigen::Vector2d> world_;   // fit_line's input
};

}  // namespace

MatchResult LegacyEapMatcher::match(const Scan& scan, const LineMap& map, const Pose2& estimate) const {
  detail::require_matchable(scan, estimate);
  const std::size_t m = map.segments.size();
  // Regions and each point's candidate segments: all of them (plain) or its grid cell's.
  std::vector<EapRegion> own_regions;
  std::vector<std::uint32_t> all_segments;
  std::span<const EapRegion> regions;
  if (index_) {
    if (!same_segments(map, index_->map())) {
      throw UsageError("EapMatcher: the map is not the one the grid index was built for");
    }
    regions = index_->regions();
  } else {
    if (m > kNoSegment) throw UsageError("EapMatcher: more than 2^32 − 1 map segments");
    own_regions.reserve(m);
    for (std::size_t j = 0; j < m; ++j) {
      try {
        own_regions.emplace_back(map.segments[j], options_.d_limit);
      } catch (const UsageError& e) {
        throw UsageError("EapMatcher: map segment " + std::to_string(j) + ": " + e.what());
      }
    }
    regions = own_regions;
    all_segments.resize(m);
    std::iota(all_segments.begin(), all_segments.end(), std::uint32_t{0});
  }

  MatchPass pass(options_, scan_points(scan, estimate), regions, map, estimate.theta + scan.sensor_pose.theta);
  const std::size_t n = pass.size();
  const auto candidates = [&](std::size_t i) -> std::span<const std::uint32_t> {
    if (index_) return index_->candidates(pass.world(i));
    return all_segments;
  };
  std::vector<std::uint32_t> members;
  members.reserve(n);
  std::vector<Hit> hits;

  if (options_.remove_claimed && options_.claim_order == ClaimOrder::kMapOrder) {
    // The thesis's loop: segment by segment in map order, deleting accepted points.
    std::vector<char> deleted(n, 0);
    if (!index_) {
      for (std::uint32_t j = 0; j < m; ++j) {
        members.clear();
        for (std::uint32_t i = 0; i < n; ++i) {
          if (deleted[i] == 0 && pass.contains(j, i)) members.push_back(i);
        }
        if (!members.empty()) pass.accept_runs(j, members, &deleted);
      }
    } else {
      // Same order and outcome, visiting only the (segment, point) pairs the grid lists.
      hits.reserve(4 * n);
      for (std::uint32_t i = 0; i < n; ++i) {
        for (const std::uint32_t j : candidates(i)) hits.push_back({j, i});
      }
      std::sort(hits.begin(), hits.end());
      std::vector<std::uint32_t> tested;
      tested.reserve(n);
      for_each_group(hits, tested, [&](std::uint32_t j, std::span<const std::uint32_t> pts) {
        members.clear();
        for (const std::uint32_t i : pts) {
          if (deleted[i] == 0 && pass.contains(j, i)) members.push_back(i);
        }
        if (!members.empty()) pass.accept_runs(j, members, &deleted);
      });
    }
    return pass.take_result();
  }

  if (options_.remove_claimed) {
    // Each point to the nearest segment among those whose ω1 holds it; candidates are
    // ascending, so a tie keeps the lower index.
    std::vector<std::uint32_t> owner(n, kNoSegment);
    for (std::uint32_t i = 0; i < n; ++i) {
      double best = 0.0;
      for (const std::uint32_t j : candidates(i)) {
        if (!pass.contains(j, i)) continue;
        const double d = pass.distance(j, i);
        if (owner[i] == kNoSegment || d < best) {
          owner[i] = j;
          best = d;
        }
      }
    }
    pass.accept_owned_runs(owner);
    return pass.take_result();
  }

  // No claims: every (segment, point) membership, grouped by segment.
  hits.reserve(2 * n);
  for (std::uint32_t i = 0; i < n; ++i) {
    for (const std::uint32_t j : candidates(i)) {
      if (pass.contains(j, i)) hits.push_back({j, i});
    }
  }
  std::sort(hits.begin(), hits.end());
  for_each_group(hits, members,
                 [&](std::uint32_t j, std::span<const std::uint32_t> pts) { pass.accept_runs(j, pts, nullptr); });
  return pass.take_result();
}

}  // namespace locbench::laser::legacy
