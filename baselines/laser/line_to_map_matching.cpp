#include "baselines/laser/line_to_map_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "baselines/laser/extraction_steps.h"
#include "baselines/laser/options_fields.h"
#include "core/angle.h"

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint, locbench::laser::SegmentMatch;
namespace {

// The line's normal form with ρ measured from `pivot` (may be negative: both forms are tried).
LineParams about(const LineParams& l, const Eigen::Vector2d& pivot) {
  return {l.rho - (std::cos(l.beta) * pivot.x() + std::sin(l.beta) * pivot.y()), l.beta};
}

// Cost of the pair when it passes the Δρ, Δβ gates, else nothing.
std::optional<double> line_cost(const LineParams& a, const LineParams& b, const LineMatchOptions& o) {
  std::optional<double> best;
  for (const bool flipped : {false, true}) {
    const double d_rho = std::abs(flipped ? a.rho + b.rho : a.rho - b.rho);
    const double d_beta = std::abs(angle_diff(a.beta, flipped ? b.beta + kPi : b.beta));
    if (d_rho > o.max_delta_rho || d_beta > o.max_delta_beta) continue;
    const double c = (d_rho / o.max_delta_rho) * (d_rho / o.max_delta_rho) +
                     (d_beta / o.max_delta_beta) * (d_beta / o.max_delta_beta);
    if (!best || c < *best) best = c;
  }
  return best;
}

bool overlaps(const LineFit& fit, const Segment& seg, const LineMatchOptions& o) {
  const double len = seg.length();
  const Eigen::Vector2d u = (seg.p2 - seg.p1) / len;
  const double t1 = u.dot(fit.first - seg.p1), t2 = u.dot(fit.last - seg.p1);
  const double lo = std::min(t1, t2), hi = std::max(t1, t2);
  const double inside = std::min(hi, len + o.end_tolerance) - std::max(lo, -o.end_tolerance);
  if (hi - lo <= 0.0) return inside >= 0.0;
  return inside >= o.min_overlap * (hi - lo);
}

}  // namespace

void validate(const LineMatchOptions& o) { validate_fields(o, "LineMatchOptions"); }

LineToMapMatches match_lines_to_map(std::span<const ExtractedLine> lines, const LineMap& map,
                                    const Eigen::Vector2d& pivot, const LineMatchOptions& options) {
  validate(options);
  LineToMapMatches out;
  out.segment_of.assign(lines.size(), std::nullopt);
  std::vector<LineParams> map_lines;
  map_lines.reserve(map.segments.size());
  for (const Segment& s : map.segments) map_lines.push_back(about(s.line(), pivot));

  for (std::size_t i = 0; i < lines.size(); ++i) {
    const LineParams line = about(lines[i].fit.line, pivot);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < map.segments.size(); ++m) {
      ++out.work;
      if (map.segments[m].length() <= 0.0) continue;
      const std::optional<double> c = line_cost(line, map_lines[m], options);
      if (!c || *c >= best || !overlaps(lines[i].fit, map.segments[m], options)) continue;
      best = *c;
      out.segment_of[i] = m;
    }
  }

  // one SegmentMatch per matched map segment, pooling its lines' points
  std::vector<Eigen::Vector2d> world;
  for (std::size_t m = 0; m < map.segments.size(); ++m) {
    SegmentMatch match;
    match.map_segment = m;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (out.segment_of[i] != m) continue;
      match.points.insert(match.points.end(), lines[i].points.begin(), lines[i].points.end());
    }
    if (match.points.empty()) continue;
    std::sort(match.points.begin(), match.points.end(),
              [](const ScanPoint& a, const ScanPoint& b) { return a.beam < b.beam; });
    world.clear();
    for (const ScanPoint& p : match.points) world.push_back(p.world);
    match.fit = fit_line(world);
    out.matches.push_back(std::move(match));
  }
  return out;
}

}  // namespace locbench::baselines::laser
