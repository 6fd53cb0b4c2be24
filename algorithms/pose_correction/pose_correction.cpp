#include "algorithms/pose_correction/pose_correction.h"

#include <cmath>
#include <limits>

#include "algorithms/pose_correction/input_checks.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::pose_correction {

// PoseCorrectionOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, PoseCorrectionOptions& o) {
  v.nested("orientation", o.orientation, "OrientationOptions");
  v.nested("position", o.position, "PositionOptions");
  v.field("iterations", o.iterations, "", at_least(1), "orientation + position rounds");
}

void validate(const PoseCorrectionOptions& o) { validate_fields(o, "PoseCorrectionOptions"); }

LOCBENCH_OPTIONS_JSON(PoseCorrectionOptions)

PoseCorrection correct_pose(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& estimate,
                            const Pose2& sensor_mount, const PoseCorrectionOptions& options) {
  validate(options);
  PoseCorrection out = uncorrected<PoseCorrection>(estimate, "correct_pose");
  Pose2 pose = estimate;
  for (int pass = 0; pass < options.iterations; ++pass) {
    out.orientation = correct_orientation(matches, map, pose, sensor_mount, options.orientation);
    out.segments_used = out.orientation.segments.size();
    if (!out.orientation.fixed) break;
    out.heading_fixed = true;
    // Eq. 6.21: re-project with the corrected heading, then the position LS.
    pose = Pose2{pose.x, pose.y, pose.theta + out.orientation.delta};
    out.position = correct_position(matches, map, pose, sensor_mount, options.position);
    out.position_fixed = out.position.fixed;
    if (out.position.fixed) pose = Pose2{pose.x + out.position.delta.x(), pose.y + out.position.delta.y(), pose.theta};
  }
  out.corrected = pose;
  out.delta = {pose.x - estimate.x, pose.y - estimate.y, angle_diff(pose.theta, estimate.theta)};

  const double inf = std::numeric_limits<double>::infinity();
  out.covariance.setZero();
  out.covariance(2, 2) = out.heading_fixed ? out.orientation.variance : inf;
  if (out.position_fixed) {
    const Eigen::Vector2d g = out.position.heading_sensitivity;
    const double v = out.orientation.variance;
    out.covariance.topLeftCorner<2, 2>() = out.position.covariance + v * g * g.transpose();
    out.covariance.block<2, 1>(0, 2) = v * g;
    out.covariance.block<1, 2>(2, 0) = v * g.transpose();
  } else {
    out.covariance(0, 0) = inf;
    out.covariance(1, 1) = inf;
  }
  return out;
}

}  // namespace locbench::pose_correction
