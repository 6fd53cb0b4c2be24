#include "pipelines/laser_scan_truth.h"

#include <cmath>

#include "algorithms/laser/line_fit.h"
#include "core/angle.h"

namespace locbench::experiments {

double MatchScore::segment_recall() const {
  return detectable == 0 ? 1.0 : static_cast<double>(detected) / static_cast<double>(detectable);
}
double MatchScore::point_precision() const {
  return points_assigned == 0 ? 1.0 : static_cast<double>(points_correct) / static_cast<double>(points_assigned);
}
double MatchScore::point_recall() const {
  return points_on_map == 0 ? 1.0 : static_cast<double>(points_correct) / static_cast<double>(points_on_map);
}

MatchScore score_match(const laser::MatchResult& result, const LineMap& map, const std::vector<int>& labels,
                       const Scan& scan, const Pose2& truth, std::size_t min_points, double min_extent) {
  MatchScore s;
  const std::size_t m = map.segments.size();
  // Detectable: enough beams on the segment, far enough apart (the matchers' acceptance rule).
  std::vector<std::vector<Eigen::Vector2d>> hits(m);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] < 0 || static_cast<std::size_t>(labels[i]) >= m || !scan.valid(i)) continue;
    ++s.points_on_map;
    hits[static_cast<std::size_t>(labels[i])].push_back(scan.point(i));
  }
  std::vector<bool> detectable(m, false);
  for (std::size_t j = 0; j < m; ++j) {
    if (hits[j].size() >= min_points && (hits[j].back() - hits[j].front()).norm() > min_extent) {
      detectable[j] = true;
      ++s.detectable;
    }
  }
  std::vector<bool> detected(m, false);
  for (const laser::SegmentMatch& match : result.matches) {
    std::size_t correct = 0;
    std::vector<Eigen::Vector2d> true_frame;
    for (const laser::ScanPoint& p : match.points) {
      ++s.points_assigned;
      if (p.beam < labels.size() && labels[p.beam] == static_cast<int>(match.map_segment)) ++correct;
      true_frame.push_back(truth * p.robot);
    }
    s.points_correct += correct;
    if (2 * correct <= match.points.size()) {
      ++s.false_matches;
      continue;
    }
    if (match.map_segment < m && detectable[match.map_segment] && !detected[match.map_segment]) {
      detected[match.map_segment] = true;
      ++s.detected;
    }
    // The extraction's own error: its points placed with the true pose, refitted, against the
    // map line (a normal pointing the other way is the same line).
    const laser::LineFit f = laser::fit_line(true_frame);
    const LineParams want = map.segments[match.map_segment].line();
    double db = angle_diff(f.line.beta, want.beta);
    double dr = f.line.rho - want.rho;
    if (std::abs(db) > kPi / 2) {
      db = angle_diff(f.line.beta + kPi, want.beta);
      dr = -f.line.rho - want.rho;
    }
    s.rho_errors.push_back(std::abs(dr));
    s.beta_errors.push_back(std::abs(db));
  }
  return s;
}

}  // namespace locbench::experiments
