#include "baselines/laser/extraction_steps.h"

#include <algorithm>
#include <cmath>

#include "baselines/laser/options_fields.h"
#include "core/errors.h"

namespace locbench::baselines::laser::detail {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint;

Eigen::Vector2d sensor_point(const ScanPoint& p) {
  return {p.range * std::cos(p.bearing), p.range * std::sin(p.bearing)};
}

std::vector<Eigen::Vector2d> sensor_points(std::span<const ScanPoint> points) {
  std::vector<Eigen::Vector2d> s;
  s.reserve(points.size());
  for (const ScanPoint& p : points) s.push_back(sensor_point(p));
  return s;
}

bool is_breakpoint(const ScanPoint& a, const ScanPoint& b, const BreakpointOptions& o) {
  const double dphi = std::abs(b.bearing - a.bearing);
  if (dphi >= o.lambda) return true;
  const double d_max = a.range * std::sin(dphi) / std::sin(o.lambda - dphi) + 3.0 * o.range_sigma;
  return (sensor_point(b) - sensor_point(a)).norm() > d_max;
}

std::vector<IndexRange> breakpoint_runs(std::span<const ScanPoint> points, const BreakpointOptions& o) {
  std::vector<IndexRange> runs;
  if (points.empty()) return runs;
  std::size_t begin = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (is_breakpoint(points[i - 1], points[i], o)) {
      runs.push_back({begin, i});
      begin = i;
    }
  }
  runs.push_back({begin, points.size()});
  return runs;
}

std::vector<std::size_t> run_index(const std::vector<IndexRange>& runs, std::size_t count) {
  std::vector<std::size_t> run_of(count, 0);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (std::size_t i = runs[r].begin; i < runs[r].end; ++i) run_of[i] = r;
  }
  return run_of;
}

std::vector<IndexRange> contiguous_pieces(std::span<const std::size_t> members, std::span<const std::size_t> run_of,
                                          std::size_t max_gap_points) {
  std::vector<IndexRange> pieces;  // ranges into `members`
  if (members.empty()) return pieces;
  std::size_t begin = 0;
  for (std::size_t k = 1; k < members.size(); ++k) {
    const std::size_t a = members[k - 1], b = members[k];
    if (run_of[a] != run_of[b] || b - a > max_gap_points + 1) {
      pieces.push_back({begin, k});
      begin = k;
    }
  }
  pieces.push_back({begin, members.size()});
  return pieces;
}

LineNormal::LineNormal(const LineParams& l) : c(std::cos(l.beta)), s(std::sin(l.beta)), rho(l.rho) {}

std::optional<LineFit> accepted_fit(std::span<const std::size_t> indices, std::span<const Eigen::Vector2d> sensor,
                                    const LineAcceptance& accept, std::vector<Eigen::Vector2d>& scratch) {
  if (indices.size() < accept.min_points || indices.size() < 2) return std::nullopt;
  scratch.clear();
  for (const std::size_t i : indices) scratch.push_back(sensor[i]);
  LineFit fit = fit_line(scratch);
  if (fit.segment().length() < accept.min_length) return std::nullopt;
  return fit;
}

bool append_if_accepted(std::span<const ScanPoint> points, std::span<const std::size_t> indices,
                        std::span<const Eigen::Vector2d> sensor, LineFrame frame, const LineAcceptance& accept,
                        std::vector<Eigen::Vector2d>& scratch, std::vector<ExtractedLine>& out) {
  if (!accepted_fit(indices, sensor, accept, scratch)) return false;
  ExtractedLine line;
  line.points.reserve(indices.size());
  scratch.clear();
  for (const std::size_t i : indices) {
    line.points.push_back(points[i]);
    scratch.push_back(frame == LineFrame::robot ? points[i].robot : points[i].world);
  }
  line.fit = fit_line(scratch);
  out.push_back(std::move(line));
  return true;
}

void sort_by_first_beam(std::vector<ExtractedLine>& lines) {
  std::sort(lines.begin(), lines.end(), [](const ExtractedLine& a, const ExtractedLine& b) {
    return a.points.front().beam < b.points.front().beam;
  });
}

void require(bool ok, const std::string& message) {
  if (!ok) throw UsageError(message);
}

}  // namespace locbench::baselines::laser::detail

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint;

void validate(const BreakpointOptions& o) { validate_fields(o, "BreakpointOptions"); }
void validate(const LineAcceptance& o) { validate_fields(o, "LineAcceptance"); }

}  // namespace locbench::baselines::laser
