#pragma once
// Position correction from matched segments (thesis §6.3, eq. 6.21–6.38), after the points were
// re-projected with the corrected heading (6.21).
//
// Sign convention: (Δx, Δy) is the correction to ADD to the estimate's position, i.e. the true
// position is (x + Δx, y + Δy) as in the thesis.
//
// Both methods minimise Σ_i Σ_j w_ij [(x_ij + Δx) cos β_i + (y_ij + Δy) sin β_i − ρ_i]² over the
// map lines (β_i, ρ_i) (eq. 5.1):
//   point-to-line (6.22–6.27): w_ij = 1, the perpendicular distance to the map line;
//   point-to-point (6.28–6.38): the distance along the beam to the "virtual scan point" where the
//   beam meets the map line, = perpendicular distance / cos θ_ij (6.34), θ_ij the angle between
//   the beam and the line's normal, so w_ij = cos⁻² θ_ij. For range noise this is the
//   maximum-likelihood weighting (the perpendicular residual's σ is σ_range·cos θ_ij).
// Normal equations (6.26 / 6.37): [k3 k4; k4 k5] (Δx, Δy)ᵀ = −(k1, k2)ᵀ, solved directly. The
// thesis's written solution Δx = (k1k5 − k2k4)/(k4² − k3k5) is right, but its
// Δy = (−k1 − k3Δx)/k4 divides by k4 = Σ w cos β sin β, which is 0 for any axis-aligned map
// (the room): there it returns NaN or rounding noise. We use Cramer's rule for both
// components: Δy = (k2k3 − k1k4)/(k4² − k3k5).
#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>

#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/units.h"

namespace locbench::pose_correction {

enum class PositionMethod {
  kPointToLine,   // eq. 6.22–6.27
  kPointToPoint,  // eq. 6.28–6.38, the thesis's choice (§6.3.3, Table 6.1)
};

struct PositionOptions {
  PositionMethod method = PositionMethod::kPointToPoint;
  // Degenerate geometry: when no two used segments differ in direction by at least this angle
  // the normal matrix is (nearly) rank 1 and the position along the lines is not determined
  // (§6.4: "matched segments parallel → no position fix"). Our value: at 10° the fix along the
  // bisector is 1/sin(10°) ≈ 5.8× less precise than across it.
  double min_angle_spread = deg(10.0);
  // Point-to-point only: cos⁻² θ_ij is capped at cos⁻²(max_incidence) (≈ 14.9 at 75°), so a
  // grazing beam — where mixed pixels and beam width dominate the range error — cannot
  // dominate the fit. Not in the thesis.
  double max_incidence = deg(75.0);
  int min_points = 3;  // segments with fewer points are ignored
  // Floor of the residual σ used for the covariance [m] (LMS 200: 5 mm, §5.4).
  double min_point_sigma = mm(5.0);
};
void to_json(nlohmann::json& j, const PositionOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, PositionOptions& o);
// Throws UsageError for an invalid option.
void validate(const PositionOptions& o);

// The sums of eq. 6.24–6.25 (k's) or 6.36 (l's) at Δ = 0, with w_ij = 1 or cos⁻² θ_ij.
struct PositionNormalEquations {
  double k1 = 0.0;           // Σ w cos β · r      (r = x cos β + y sin β − ρ, the signed residual)
  double k2 = 0.0;           // Σ w sin β · r
  double k3 = 0.0;           // Σ w cos² β
  double k4 = 0.0;           // Σ w cos β sin β
  double k5 = 0.0;           // Σ w sin² β
  double weighted_ss = 0.0;  // Σ w r² at Δ = 0 [m²]
  // ∂(k1, k2)/∂θ: how the sums move when the heading of the re-projection changes [m/rad],
  // for the heading term of the covariance.
  Eigen::Vector2d dk_dtheta = Eigen::Vector2d::Zero();
  std::size_t points = 0;
  std::size_t segments = 0;
  double angle_spread = 0.0;  // largest angle between two used segments' directions [rad]

  Eigen::Matrix2d matrix() const { return (Eigen::Matrix2d() << k3, k4, k4, k5).finished(); }
  Eigen::Vector2d rhs() const { return {-k1, -k2}; }
};

// The sums for the points of `matches` re-projected with `pose` (eq. 6.21: the estimate with
// the corrected heading) through their robot-frame coordinates; beams for θ_ij leave from
// pose ∘ sensor_mount at bearing + pose.θ + sensor_mount.θ. Segments with fewer than
// options.min_points points are skipped. Throws UsageError for a match naming a segment the
// map does not have.
PositionNormalEquations position_normal_equations(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                                  const Pose2& pose, const Pose2& sensor_mount,
                                                  const PositionOptions& options);

struct PositionCorrection {
  bool fixed = false;                               // false: no segments, or all (nearly) parallel
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();  // (Δx, Δy) [m]
  // Covariance of delta for a known heading: s² A⁻¹ with A the normal matrix and s² the
  // weighted residual variance Σ w r² / (N − 2) at the solution, floored at min_point_sigma².
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  // ∂Δ/∂θ [m/rad]: an error e in the corrected heading moves the fix by e·heading_sensitivity.
  Eigen::Vector2d heading_sensitivity = Eigen::Vector2d::Zero();
  double residual_sigma = 0.0;  // s [m], before the floor
  double angle_spread = 0.0;    // [rad]
  std::size_t segments_used = 0;
  std::size_t points_used = 0;
};

// Solves the normal equations (6.26 / 6.37) for the points re-projected with `pose`.
PositionCorrection correct_position(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& pose,
                                    const Pose2& sensor_mount, const PositionOptions& options = {});

}  // namespace locbench::pose_correction
