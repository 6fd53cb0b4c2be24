#pragma once
// Chapter 6's pose correction from matched segments: heading by weighted least squares (§6.2,
// eq. 6.1–6.20), then position by point-to-line or point-to-point least squares on the points
// re-projected with the corrected heading (§6.3, eq. 6.21–6.38). When the used segments are
// all (nearly) parallel the position is not determined and the correction is heading-only
// (§6.4–6.5).
//
// Sign convention: corrected = (x + Δx, y + Δy, θ + Δθ) with (Δx, Δy, Δθ) = `delta`; for
// noise-free points and a heading error below 90° the corrected pose is the true pose.
#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>

#include "algorithms/laser/segment_match.h"
#include "algorithms/pose_correction/orientation_correction.h"
#include "algorithms/pose_correction/position_correction.h"
#include "core/line_map.h"
#include "core/pose2.h"

namespace locbench::pose_correction {

struct PoseCorrectionOptions {
  OrientationOptions orientation;
  PositionOptions position;
  // 1 = one pass as in the thesis. More passes repeat heading and position from the corrected
  // pose (the weights of eq. 6.18 depend on the position, θ_ij on the heading); the result is
  // the total correction from the original estimate.
  int iterations = 1;
};
void to_json(nlohmann::json& j, const PoseCorrectionOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, PoseCorrectionOptions& o);
void validate(const PoseCorrectionOptions& o);

struct PoseCorrection {
  Pose2 corrected;                                  // estimate + delta
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();  // (Δx, Δy, Δθ) added to the estimate
  bool heading_fixed = false;
  bool position_fixed = false;
  // Covariance of `corrected` [m², m², rad²]: θθ = var(Δθ̂) (orientation_correction.h), the
  // position block = the position LS covariance + g var(Δθ̂) gᵀ and the cross terms g var(Δθ̂),
  // g = ∂Δ/∂θ (the heading error carried into the position fix; first order, treating the
  // heading and position residuals as independent). Components that are not fixed have +∞ on
  // the diagonal and 0 off it.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  std::size_t segments_used = 0;  // segments in the heading estimate (last pass)
  // Details of the last pass.
  OrientationCorrection orientation;
  PositionCorrection position;
};

// One correction of `estimate` from `matches` (points in the robot frame; their world field is
// recomputed under the estimate). `sensor_mount` = Scan::sensor_pose (the beams' origin in the
// robot frame; identity in the thesis). No usable segment → corrected = estimate, nothing fixed.
// Throws UsageError for invalid options, a non-finite estimate or a match naming a segment the
// map does not have.
PoseCorrection correct_pose(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& estimate,
                            const Pose2& sensor_mount = Pose2::identity(), const PoseCorrectionOptions& options = {});

}  // namespace locbench::pose_correction
