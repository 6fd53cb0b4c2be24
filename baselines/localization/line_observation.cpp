#include "baselines/localization/line_observation.h"

#include <algorithm>
#include <cmath>

#include "algorithms/laser/line_fit.h"
#include "core/angle.h"
#include "core/errors.h"

namespace locbench::baselines::localization {

LineObservation line_observation(std::span<const Eigen::Vector2d> robot_points, double min_sigma) {
  if (!(min_sigma > 0.0)) throw UsageError("line_observation: min_sigma must be > 0 m");
  if (robot_points.size() < 2) throw UsageError("line_observation: needs at least 2 points");
  const locbench::laser::LineFit fit = locbench::laser::fit_line(robot_points);
  const double n = static_cast<double>(robot_points.size());
  double ss_along = 0.0;
  for (const auto& p : robot_points) ss_along += std::pow(fit.direction.dot(p - fit.centroid), 2);
  if (!(ss_along > 0.0)) throw UsageError("line_observation: the points coincide");
  const double ss_perp = fit.rms * fit.rms * n;
  const double sigma2 = std::max(robot_points.size() > 2 ? ss_perp / (n - 2.0) : 0.0, min_sigma * min_sigma);
  LineObservation z;
  z.alpha = fit.line.beta;
  z.r = fit.line.rho;
  // t_c = ∂r/∂α = (−sin α, cos α)·c: the centroid's coordinate along the line.
  const double t_c = -std::sin(z.alpha) * fit.centroid.x() + std::cos(z.alpha) * fit.centroid.y();
  const double var_alpha = sigma2 / ss_along;
  z.covariance << var_alpha, t_c * var_alpha,  //
      t_c * var_alpha, sigma2 / n + t_c * t_c * var_alpha;
  return z;
}

std::vector<LineObservation> line_observations(std::span<const locbench::laser::SegmentMatch> matches, double min_sigma,
                                               int min_points) {
  if (!(min_sigma > 0.0)) throw UsageError("line_observations: min_sigma must be > 0 m");
  std::vector<LineObservation> out;
  std::vector<Eigen::Vector2d> pts;
  for (const auto& m : matches) {
    if (m.points.size() < static_cast<std::size_t>(std::max(min_points, 2))) continue;
    pts.clear();
    for (const auto& p : m.points) pts.push_back(p.robot);
    try {
      out.push_back(line_observation(pts, min_sigma));
    } catch (const UsageError&) {
      // coincident points: no line
    }
  }
  return out;
}

LinePrediction predict_line(const LineParams& map_line, const Pose2& pose) {
  const double c = std::cos(map_line.beta), s = std::sin(map_line.beta);
  LinePrediction h;
  h.z = {wrap_angle(map_line.beta - pose.theta), map_line.rho - (pose.x * c + pose.y * s)};
  h.jacobian << 0.0, 0.0, -1.0,  //
      -c, -s, 0.0;
  if (h.z(1) < 0.0) {
    h.flipped = true;
    h.z = {wrap_angle(h.z(0) + kPi), -h.z(1)};
    h.jacobian.row(1) *= -1.0;
  }
  return h;
}

Eigen::Vector2d line_innovation(const LineObservation& z, const LinePrediction& predicted) {
  return {angle_diff(z.alpha, predicted.z(0)), z.r - predicted.z(1)};
}

}  // namespace locbench::baselines::localization
