#pragma once
// Steps every extractor shares: sensor-frame coordinates, breakpoint runs, splitting a point
// set into contiguous pieces, and accepting and fitting a piece as an ExtractedLine. Internal
// to the laser baselines (tested through the extractors).
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "baselines/laser/line_extraction.h"

namespace locbench::baselines::laser::detail {

// A half-open range of indices into the point list.
struct IndexRange {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};

// The point in the sensor frame, from its polar measurement.
Eigen::Vector2d sensor_point(const locbench::laser::ScanPoint& p);
std::vector<Eigen::Vector2d> sensor_points(std::span<const locbench::laser::ScanPoint> points);

// Adaptive breakpoint test between consecutive points a (earlier) and b (see BreakpointOptions).
bool is_breakpoint(const locbench::laser::ScanPoint& a, const locbench::laser::ScanPoint& b,
                   const BreakpointOptions& o);
// The runs of points between breakpoints, in order; together they cover every point.
std::vector<IndexRange> breakpoint_runs(std::span<const locbench::laser::ScanPoint> points, const BreakpointOptions& o);
// run_of[i] = index of the run that holds point i.
std::vector<std::size_t> run_index(const std::vector<IndexRange>& runs, std::size_t count);

// Splits ascending point indices into pieces that are contiguous in the scan: consecutive
// members stay together when they are in the same run and skip at most `max_gap_points`.
std::vector<IndexRange> contiguous_pieces(std::span<const std::size_t> members, std::span<const std::size_t> run_of,
                                          std::size_t max_gap_points);

// A line (ρ, β) with its normal's cosine and sine evaluated once, for inner loops.
struct LineNormal {
  double c = 1.0, s = 0.0, rho = 0.0;
  LineNormal() = default;
  explicit LineNormal(const LineParams& l);
  // Perpendicular distance of p from the line.
  double distance(const Eigen::Vector2d& p) const { return std::abs(c * p.x() + s * p.y() - rho); }
};

// The sensor-frame least-squares line of sensor[indices] if it passes `accept` (count, and
// first-to-last length), else nothing. `scratch` is reused storage.
std::optional<locbench::laser::LineFit> accepted_fit(std::span<const std::size_t> indices,
                                                     std::span<const Eigen::Vector2d> sensor,
                                                     const LineAcceptance& accept,
                                                     std::vector<Eigen::Vector2d>& scratch);

// Appends the line through points[indices] (ascending) to `out` when it passes `accept`
// (count and first-to-last length measured on the sensor-frame points); the fit is made in
// `frame`. `scratch` is reused storage. Returns whether it was accepted.
bool append_if_accepted(std::span<const locbench::laser::ScanPoint> points, std::span<const std::size_t> indices,
                        std::span<const Eigen::Vector2d> sensor, LineFrame frame, const LineAcceptance& accept,
                        std::vector<Eigen::Vector2d>& scratch, std::vector<ExtractedLine>& out);

// Orders lines by their first beam.
void sort_by_first_beam(std::vector<ExtractedLine>& lines);

void require(bool ok, const std::string& message);  // throws UsageError(message) when !ok

}  // namespace locbench::baselines::laser::detail
