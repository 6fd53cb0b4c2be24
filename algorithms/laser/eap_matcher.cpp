#include "algorithms/laser/eap_matcher.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "algorithms/laser/eap_matcher_moments.h"
#include "algorithms/laser/eap_matcher_points.h"
#include "algorithms/laser/eap_matcher_segments.h"
#include "algorithms/laser/eap_matcher_steps.h"
#include "core/errors.h"

namespace locbench::laser {
namespace {

// The point indices first … last − 1 as a range (what accept_run reads of a run): std::views::iota
// did this, but clang 14 cannot instantiate libstdc++ 12's iota_view (the fuzz build).
struct IndexRange {
  std::uint32_t first, last;
  struct Iterator {
    std::uint32_t i;
    std::uint32_t operator*() const { return i; }
    Iterator& operator++() {
      ++i;
      return *this;
    }
    bool operator==(const Iterator&) const = default;
  };
  Iterator begin() const { return {first}; }
  Iterator end() const { return {last}; }
  std::size_t size() const { return last - first; }
  std::uint32_t operator[](std::size_t k) const { return first + static_cast<std::uint32_t>(k); }
};

using detail::BearingCache;
using detail::consecutive;
using detail::EapSegmentTable;
using detail::FlatPoints;
using detail::for_each_group;
using detail::Hit;
using detail::Moments;
using detail::PrincipalAxis;
using detail::same_segments;

constexpr std::uint32_t kNoSegment = static_cast<std::uint32_t>(-1);
constexpr std::size_t kMaskBits = 64;  // segments per branch-free band-test block

struct Run {
  std::uint32_t segment, begin, end;  // points [begin, end)
  Moments moments;                    // about the segment's midpoint
  bool operator<(const Run& o) const { return segment != o.segment ? segment < o.segment : begin < o.begin; }
};

// Buffers reused across calls, one set per thread (so one matcher can still be shared across
// threads): the bearing cache, the points, the plain matcher's last segment table.
struct Workspace {
  BearingCache trig;
  FlatPoints points;
  EapSegmentTable plain_table;
  std::vector<std::uint32_t> owner, members, tested, accepted;
  std::vector<std::uint64_t> masks;  // per point: band-test bits of a block of segments
  std::vector<double> best2;         // per point: squared distance to its owner
  std::vector<char> deleted;
  std::vector<Hit> hits;
  std::vector<Run> runs;
};

Workspace& workspace() {
  thread_local Workspace ws;
  return ws;
}

// sqrt(d2) < sqrt(best2) — the old comparison of distances — decided on the squares: sqrt is
// monotone, so only near-ties (relative gap < 1e-9, where two squares may round to one root)
// need the roots.
bool nearer(double d2, double best2) {
  if (!(d2 < best2)) return false;
  return d2 < best2 * (1.0 - 1e-9) || std::sqrt(d2) < std::sqrt(best2);
}

// One match() call over the flat points and segments.
class MatchPass {
 public:
  MatchPass(const EapOptions& o, const EapSegmentTable& table, const Scan& scan, const LineMap& map,
            double sensor_heading, Workspace& ws)
      : o_(o),
        t_(table),
        scan_(scan),
        map_(map),
        p_(ws.points),
        ws_(ws),
        sensor_heading_(sensor_heading),
        sin_max_direction_(std::sin(o.max_direction_error)) {}

  // Calls f(j) for each segment j whose ω1 holds point i, ascending j: the band test first
  // (branch-free over blocks of 64 segments, plain) or the grid cell's list (indexed).
  template <class F>
  void for_each_region(std::size_t i, const SegmentGridIndex* index, F&& f) {
    const double px = p_.x[i], py = p_.y[i];
    if (index == nullptr) {
      const std::size_t m = t_.size();
      for (std::size_t first = 0; first < m; first += kMaskBits) {
        std::uint64_t mask = t_.band_mask(first, std::min(kMaskBits, m - first), px, py);
        while (mask != 0) {
          const std::size_t j = first + static_cast<std::size_t>(std::countr_zero(mask));
          mask &= mask - 1;
          if (t_.in_caps(j, px, py, o_.region)) f(static_cast<std::uint32_t>(j));
        }
      }
      result_.work += m;
      return;
    }
    const auto candidates = index->candidates(Eigen::Vector2d(px, py));
    result_.work += candidates.size();
    for (const std::uint32_t j : candidates) {
      if (t_.contains(j, px, py, o_.region)) f(j);
    }
  }

  // Nearest-segment claims: the owner of each point (kNoSegment for none). Plain: the band
  // tests of a block of 64 segments against all points first (EapSegmentTable::band_masks),
  // then the end caps and distances of the few in-band pairs; indexed: the grid cell's list.
  void claim_nearest(const SegmentGridIndex* index, std::vector<std::uint32_t>& owner) {
    const std::size_t n = p_.size();
    owner.assign(n, kNoSegment);
    std::vector<double>& best2 = ws_.best2;  // < 0: not computed yet (a single candidate)
    best2.assign(n, -1.0);
    const auto consider = [&](std::size_t i, std::uint32_t j) {
      const double x = p_.x[i], y = p_.y[i];
      if (owner[i] == kNoSegment) {  // most points lie in one ω1: no distance needed
        owner[i] = j;
        return;
      }
      if (best2[i] < 0.0) best2[i] = t_.distance_squared(owner[i], x, y);
      const double d2 = t_.distance_squared(j, x, y);
      if (nearer(d2, best2[i])) {
        owner[i] = j;
        best2[i] = d2;
      }
    };
    if (index != nullptr) {
      for (std::size_t i = 0; i < n; ++i) {
        for_each_region(i, index, [&](std::uint32_t j) { consider(i, j); });
      }
      return;
    }
    const std::size_t m = t_.size();
    std::vector<std::uint64_t>& masks = ws_.masks;
    const RegionRule rule = o_.region;
    for (std::size_t first = 0; first < m; first += kMaskBits) {
      masks.assign(n, 0);
      t_.band_masks(first, std::min(kMaskBits, m - first), p_.x.data(), p_.y.data(), n, masks.data());
      for (std::size_t i = 0; i < n; ++i) {
        for (std::uint64_t mask = masks[i]; mask != 0; mask &= mask - 1) {
          const auto j = static_cast<std::uint32_t>(first + std::countr_zero(mask));
          if (t_.in_caps(j, p_.x[i], p_.y[i], rule)) consider(i, j);
        }
      }
    }
    result_.work += n * m;
  }

  // Whether point i is in ω1 of segment j, counted as one membership test.
  bool contains(std::uint32_t j, std::size_t i) {
    ++result_.work;
    return t_.contains(j, p_.x[i], p_.y[i], o_.region);
  }

  // Runs of `members` (ascending point indices, all inside ω1 of `segment`), accepted (§5.3
  // conditions 1–3 and ours) into one SegmentMatch. Two members are consecutive when every
  // valid point between them is deleted (`deleted` null: only adjacent points are). Accepted
  // points are marked in `deleted` when it is given.
  void accept_runs(std::uint32_t segment, std::span<const std::uint32_t> members, std::vector<char>* deleted) {
    std::vector<std::uint32_t>& accepted = ws_.accepted;
    accepted.clear();
    Moments sum;
    std::size_t begin = 0;
    while (begin < members.size()) {
      std::size_t end = begin + 1;
      while (end < members.size() && consecutive(members[end - 1], members[end], deleted)) ++end;
      const std::span<const std::uint32_t> run = members.subspan(begin, end - begin);
      Moments m;
      if (accept_run(segment, run, m)) {
        accepted.insert(accepted.end(), run.begin(), run.end());
        sum += m;
      }
      begin = end;
    }
    if (deleted != nullptr) {
      for (const std::uint32_t i : accepted) (*deleted)[i] = 1;
    }
    emit(segment, accepted, sum);
  }

  // Nearest-segment claims: a run is a maximal range of adjacent points with one owner; the
  // accepted ones are reported per segment, segments ascending.
  void accept_owned_runs(std::span<const std::uint32_t> owner) {
    std::vector<Run>& runs = ws_.runs;
    runs.clear();
    const auto n = static_cast<std::uint32_t>(owner.size());
    std::uint32_t begin = 0;
    while (begin < n) {
      std::uint32_t end = begin + 1;
      while (end < n && owner[end] == owner[begin]) ++end;
      Moments m;
      if (owner[begin] != kNoSegment && accept_run(owner[begin], IndexRange{begin, end}, m)) {
        runs.push_back({owner[begin], begin, end, m});
      }
      begin = end;
    }
    std::sort(runs.begin(), runs.end());
    std::size_t groups = 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      groups += k == 0 || runs[k].segment != runs[k - 1].segment;
    }
    result_.matches.reserve(groups);
    std::vector<std::uint32_t>& accepted = ws_.accepted;
    for (std::size_t k = 0; k < runs.size();) {
      const std::uint32_t segment = runs[k].segment;
      accepted.clear();
      Moments sum;
      for (; k < runs.size() && runs[k].segment == segment; ++k) {
        for (std::uint32_t i = runs[k].begin; i < runs[k].end; ++i) accepted.push_back(i);
        sum += runs[k].moments;
      }
      emit(segment, accepted, sum);
    }
  }

  MatchResult take_result() { return std::move(result_); }

 private:
  // §5.3: score Σ g ≥ C_limit (5.6, w = 1 inside ω1; with g ≡ 1 the point count) and the first
  // and last point more than min_extent apart; ours: the run's LS direction within
  // max_direction_error of the segment's. Cheapest test first. `m` gets the run's moments
  // about the segment's midpoint (the fit reuses them).
  // `run`: ascending point indices (a span, or an iota range for a contiguous run).
  template <class Points>
  bool accept_run(std::uint32_t segment, const Points& run, Moments& m) const {
    const bool count = o_.weighting.kind == HoughWeighting::kCount;
    if (count && !(static_cast<double>(run.size()) >= o_.c_limit)) return false;  // (5.11)
    const std::uint32_t a = run[0], b = run[run.size() - 1];
    if (!(Eigen::Vector2d(p_.x[b] - p_.x[a], p_.y[b] - p_.y[a]).norm() > o_.min_extent)) {
      return false;
    }
    const double ox = t_.mid_x(segment), oy = t_.mid_y(segment);
    m = Moments{};
    for (const std::uint32_t i : run) m.add(p_.x[i] - ox, p_.y[i] - oy);
    if (o_.max_direction_error > 0.0) {
      const PrincipalAxis f = detail::principal_axis(m);
      const double cross = t_.dx(segment) * f.uy - t_.dy(segment) * f.ux;
      if (std::abs(cross) > sin_max_direction_) return false;
    }
    if (count) return true;
    const double beta = map_.segments[segment].line().beta;
    double score = 0.0;
    for (const std::uint32_t i : run) {
      score += hough_weight(p_.point(i, scan_), sensor_heading_, beta, o_.weighting);
    }
    return score >= o_.c_limit;
  }

  // One SegmentMatch of `segment` with the points `indices` (ascending; consumed) whose moments
  // are `m`: the LS line from the moments; ours: while the point farthest from it is beyond
  // trim_distance, that point is removed from the moments and the line recomputed; a match
  // left with fewer than max(2, c_limit) points is dropped.
  void emit(std::uint32_t segment, std::vector<std::uint32_t>& indices, Moments m) {
    if (indices.empty()) return;
    const double ox = t_.mid_x(segment), oy = t_.mid_y(segment);
    PrincipalAxis a = detail::principal_axis(m);
    double ss = 0.0;
    for (;;) {
      const double nx = -a.uy, ny = a.ux;
      const double cx = ox + a.mean_x, cy = oy + a.mean_y;
      std::size_t worst = 0;
      double worst_r = -1.0;
      ss = 0.0;
      for (std::size_t k = 0; k < indices.size(); ++k) {
        const std::uint32_t i = indices[k];
        const double r = std::abs(nx * (p_.x[i] - cx) + ny * (p_.y[i] - cy));
        ss += r * r;
        if (r > worst_r) {
          worst_r = r;
          worst = k;
        }
      }
      if (!(o_.trim_distance > 0.0) || worst_r <= o_.trim_distance) break;
      const std::uint32_t i = indices[worst];
      m.remove(p_.x[i] - ox, p_.y[i] - oy);
      indices.erase(indices.begin() + static_cast<std::ptrdiff_t>(worst));
      if (static_cast<double>(indices.size()) < std::max(2.0, o_.c_limit)) return;
      a = detail::principal_axis(m);
    }
    SegmentMatch match;
    match.map_segment = segment;
    match.points.reserve(indices.size());
    for (const std::uint32_t i : indices) match.points.push_back(p_.point(i, scan_));
    match.fit = detail::line_fit_from(m, a, ox, oy, ss, match.points.front().world, match.points.back().world);
    result_.matches.push_back(std::move(match));
  }

  const EapOptions& o_;
  const EapSegmentTable& t_;
  const Scan& scan_;
  const LineMap& map_;
  const FlatPoints& p_;
  Workspace& ws_;
  double sensor_heading_;
  double sin_max_direction_;
  MatchResult result_;
};

}  // namespace

EapMatcher::EapMatcher(EapOptions options) : options_(options) { validate(options_); }

EapMatcher::EapMatcher(std::shared_ptr<const SegmentGridIndex> index, EapOptions options)
    : options_(options), index_(std::move(index)) {
  validate(options_);
  if (!index_) throw UsageError("EapMatcher: the grid index is null");
  if (index_->d_limit() != options_.d_limit) {
    throw UsageError("EapMatcher: the grid index was built for d_limit " + std::to_string(index_->d_limit()) +
                     " m, the options say " + std::to_string(options_.d_limit) + " m");
  }
  auto table = std::make_shared<EapSegmentTable>();
  table->assign(index_->regions());
  table_ = std::move(table);
}

MatchResult EapMatcher::match(const Scan& scan, const LineMap& map, const Pose2& estimate) const {
  detail::require_matchable(scan, estimate);
  Workspace& ws = workspace();
  const EapSegmentTable* table = table_.get();
  const SegmentGridIndex* index = index_.get();
  if (index != nullptr) {
    if (!same_segments(map, index->map())) {
      throw UsageError("EapMatcher: the map is not the one the grid index was built for");
    }
  } else {
    if (map.segments.size() > kNoSegment) {
      throw UsageError("EapMatcher: more than 2^32 − 1 map segments");
    }
    if (!ws.plain_table.built_from(map, options_.d_limit)) {
      try {
        ws.plain_table.assign(map, options_.d_limit);
      } catch (const UsageError& e) {
        throw UsageError(std::string("EapMatcher: ") + e.what());
      }
    }
    table = &ws.plain_table;
  }
  ws.trig.update(scan.bearings);
  ws.points.assign(scan, estimate, ws.trig);

  MatchPass pass(options_, *table, scan, map, estimate.theta + scan.sensor_pose.theta, ws);
  const std::size_t n = ws.points.size();
  const auto m = static_cast<std::uint32_t>(table->size());

  if (options_.remove_claimed && options_.claim_order == ClaimOrder::kNearestSegment) {
    // Each point to the nearest segment among those whose ω1 holds it (ties → lower index).
    pass.claim_nearest(index, ws.owner);
    pass.accept_owned_runs(ws.owner);
    return pass.take_result();
  }

  if (options_.remove_claimed) {
    // The thesis's loop: segment by segment in map order, deleting accepted points.
    ws.deleted.assign(n, 0);
    if (index == nullptr) {
      for (std::uint32_t j = 0; j < m; ++j) {
        ws.members.clear();
        for (std::uint32_t i = 0; i < n; ++i) {
          if (ws.deleted[i] == 0 && pass.contains(j, i)) ws.members.push_back(i);
        }
        if (!ws.members.empty()) pass.accept_runs(j, ws.members, &ws.deleted);
      }
    } else {
      // Same order and outcome, visiting only the (segment, point) pairs the grid lists.
      ws.hits.clear();
      for (std::uint32_t i = 0; i < n; ++i) {
        for (const std::uint32_t j : index->candidates({ws.points.x[i], ws.points.y[i]})) {
          ws.hits.push_back({j, i});
        }
      }
      std::sort(ws.hits.begin(), ws.hits.end());
      for_each_group(ws.hits, ws.tested, [&](std::uint32_t j, std::span<const std::uint32_t> pts) {
        ws.members.clear();
        for (const std::uint32_t i : pts) {
          if (ws.deleted[i] == 0 && pass.contains(j, i)) ws.members.push_back(i);
        }
        if (!ws.members.empty()) pass.accept_runs(j, ws.members, &ws.deleted);
      });
    }
    return pass.take_result();
  }

  // No claims: every (segment, point) membership, grouped by segment.
  ws.hits.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    pass.for_each_region(i, index, [&](std::uint32_t j) { ws.hits.push_back({j, i}); });
  }
  std::sort(ws.hits.begin(), ws.hits.end());
  for_each_group(ws.hits, ws.members,
                 [&](std::uint32_t j, std::span<const std::uint32_t> pts) { pass.accept_runs(j, pts, nullptr); });
  return pass.take_result();
}

}  // namespace locbench::laser
