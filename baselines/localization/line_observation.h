#pragma once
// Line features for the slides' Kalman localization (Siegwart & Nourbakhsh ch. 5, "用于机器人
// 定位的卡尔曼滤波"): an observed line z_j = (α_j, r_j) in the ROBOT frame with covariance Σ_R,j,
// and the measurement prediction h_i of a map line (α_t,i, r_t,i) from a pose estimate.
//
// Frames: observations are fitted to ScanPoint::robot, which scan_points() already computed
// through the sensor mount (eq. 5.2), so they are in the robot frame and h_i needs no mount
// term. Normal form x cos α + y sin α = r with r ≥ 0 (eq. 5.1), α ∈ [−π, π).
#include <Eigen/Core>
#include <span>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "core/pose2.h"
#include "core/segment.h"
#include "core/units.h"

namespace locbench::baselines::localization {

struct LineObservation {
  double alpha = 0.0;                                    // normal direction [rad], robot frame
  double r = 0.0;                                        // distance from the robot centre [m], ≥ 0
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // Σ_R over (α, r)
};

// Orthogonal LS line through robot-frame points (locbench::laser::fit_line) with its first-order
// covariance for independent perpendicular point noise σ²: var α = σ²/Σ(t − t̄)²,
// var r = σ²/N + t_c² var α, cov(α, r) = t_c var α, where t is the coordinate along the line and
// t_c the centroid's (r = nᵀc, ∂r/∂α = t_c). σ² = max(Σ residual²/(N − 2), min_sigma²).
// Throws UsageError for fewer than 2 distinct points or min_sigma <= 0.
LineObservation line_observation(std::span<const Eigen::Vector2d> robot_points, double min_sigma = mm(5.0));
// One observation per match with at least `min_points` points (the map segment it was matched
// to is ignored: the localizer associates by its validation gate).
std::vector<LineObservation> line_observations(std::span<const locbench::laser::SegmentMatch> matches,
                                               double min_sigma = mm(5.0), int min_points = 3);

// h_i and ∇h_i of a map line (β, ρ) seen from `pose` (slides):
//   h = [β − θ, ρ − (x cos β + y sin β)],  ∇h = [[0, 0, −1], [−cos β, −sin β, 0]].
// When the robot is on the far side of the line from the world origin the predicted r is
// negative; it is then flipped to the observable form (α + π, −r), which negates the r row of
// the Jacobian: [cos β, sin β, 0]. α is wrapped to [−π, π).
struct LinePrediction {
  Eigen::Vector2d z = Eigen::Vector2d::Zero();  // (α, r), r ≥ 0
  Eigen::Matrix<double, 2, 3> jacobian = Eigen::Matrix<double, 2, 3>::Zero();
  bool flipped = false;
};
LinePrediction predict_line(const LineParams& map_line, const Pose2& pose);

// z − ẑ with the α component wrapped to [−π, π).
Eigen::Vector2d line_innovation(const LineObservation& z, const LinePrediction& predicted);

}  // namespace locbench::baselines::localization
