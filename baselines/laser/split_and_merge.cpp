#include "baselines/laser/split_and_merge.h"

#include <cmath>
#include <numeric>

#include "baselines/laser/extraction_steps.h"
#include "baselines/laser/options_fields.h"

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint;
namespace {

using detail::IndexRange;

// Largest perpendicular residual of s[r] about its least-squares line.
double max_residual(std::span<const Eigen::Vector2d> s, IndexRange r, std::size_t& work) {
  const auto pts = s.subspan(r.begin, r.size());
  const LineFit f = fit_line(pts);
  double worst = 0.0;
  const detail::LineNormal line(f.line);
  for (const auto& p : pts) worst = std::max(worst, line.distance(p));
  work += 2 * pts.size();
  return worst;
}

// Interior index of r farthest from the chord s[begin] → s[end − 1].
std::size_t split_point(std::span<const Eigen::Vector2d> s, IndexRange r, std::size_t& work) {
  const Eigen::Vector2d a = s[r.begin], b = s[r.end - 1];
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  std::size_t best = r.begin + 1;
  double best_dist = -1.0;
  for (std::size_t i = r.begin + 1; i + 1 < r.end; ++i) {
    const Eigen::Vector2d v = s[i] - a;
    const double dist = len > 0.0 ? std::abs(d.x() * v.y() - d.y() * v.x()) / len : v.norm();
    if (dist > best_dist) {
      best_dist = dist;
      best = i;
    }
  }
  work += r.size();
  return best;
}

// Step 1 on one run: the leaves of the recursive split, in scan order.
void split_run(std::span<const Eigen::Vector2d> s, IndexRange run, double split_distance,
               std::vector<IndexRange>& stack, std::vector<IndexRange>& leaves, std::size_t& work) {
  stack.clear();
  stack.push_back(run);
  while (!stack.empty()) {
    const IndexRange r = stack.back();
    stack.pop_back();
    if (r.size() < 3 || max_residual(s, r, work) <= split_distance) {
      leaves.push_back(r);
      continue;
    }
    const std::size_t p = split_point(s, r, work);
    stack.push_back({p + 1, r.end});  // right half after the left one: leaves stay in order
    stack.push_back({r.begin, p + 1});
  }
}

// Step 2: merges adjacent leaves of one run while their union stays within split_distance.
void merge_collinear(std::span<const Eigen::Vector2d> s, double split_distance, std::vector<IndexRange>& sets,
                     std::size_t& work) {
  std::size_t out = 0;
  for (std::size_t i = 1; i < sets.size(); ++i) {
    const IndexRange joined{sets[out].begin, sets[i].end};
    if (max_residual(s, joined, work) <= split_distance) {
      sets[out] = joined;
    } else {
      sets[++out] = sets[i];
    }
  }
  if (!sets.empty()) sets.resize(out + 1);
}

// Step 3a: a boundary point goes to whichever of the two adjacent sets' lines (fitted
// without it) is nearer. The split puts the farthest point on the left whichever wall it is on,
// and near a corner a point of the other wall can be within split_distance of this one's line.
void refine_boundaries(std::span<const Eigen::Vector2d> s, std::vector<IndexRange>& sets, std::size_t& work) {
  const auto dist_to_fit = [&](std::size_t q, IndexRange r) {
    const LineFit f = fit_line(s.subspan(r.begin, r.size()));
    work += r.size() + 1;
    return detail::LineNormal(f.line).distance(s[q]);
  };
  for (std::size_t k = 0; k + 1 < sets.size(); ++k) {
    IndexRange& a = sets[k];
    IndexRange& b = sets[k + 1];
    if (a.end != b.begin) continue;
    for (int moves = 0; moves < 3 && a.size() > 2; ++moves) {  // a's last point to b?
      const std::size_t q = a.end - 1;
      if (!(dist_to_fit(q, b) < dist_to_fit(q, {a.begin, q}))) break;
      --a.end;
      --b.begin;
    }
    for (int moves = 0; moves < 3 && b.size() > 2; ++moves) {  // b's first point to a?
      const std::size_t q = b.begin;
      if (!(dist_to_fit(q, a) < dist_to_fit(q, {q + 1, b.end}))) break;
      ++a.end;
      ++b.begin;
    }
  }
}

}  // namespace

void validate(const SplitAndMergeOptions& o) { validate_fields(o, "SplitAndMergeOptions"); }

ExtractionResult split_and_merge(std::span<const ScanPoint> points, LineFrame frame,
                                 const SplitAndMergeOptions& options) {
  validate(options);
  ExtractionResult result;
  const std::vector<Eigen::Vector2d> s = detail::sensor_points(points);
  const std::vector<IndexRange> runs = detail::breakpoint_runs(points, options.breakpoints);
  result.work += points.size();

  std::vector<IndexRange> stack, sets;
  std::vector<std::size_t> indices;
  std::vector<Eigen::Vector2d> scratch;
  for (const IndexRange& run : runs) {
    if (run.size() < options.acceptance.min_points) continue;  // too short for any line
    sets.clear();
    split_run(s, run, options.split_distance, stack, sets, result.work);
    merge_collinear(s, options.split_distance, sets, result.work);
    refine_boundaries(s, sets, result.work);
    for (const IndexRange& set : sets) {  // step 3: refit and accept
      indices.resize(set.size());
      std::iota(indices.begin(), indices.end(), set.begin);
      detail::append_if_accepted(points, indices, s, frame, options.acceptance, scratch, result.lines);
    }
  }
  return result;
}

}  // namespace locbench::baselines::laser
