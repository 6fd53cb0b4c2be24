#pragma once
// Trajectory error metrics in evo's vocabulary: absolute pose error (APE) against a reference
// trajectory and relative pose error against reference relations (Kümmerle et al. 2009).
#include <span>
#include <vector>

#include "core/sensor_data.h"
#include "core/trajectory.h"

namespace locbench {

// Per-pose errors: translation [m] and absolute rotation [rad].
struct PoseErrors {
  std::vector<double> t;
  std::vector<double> translation;
  std::vector<double> rotation;
};

// evo's statistics of one error series.
struct ErrorStatistics {
  std::size_t n = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, std = 0.0, min = 0.0, max = 0.0, sse = 0.0;
};
ErrorStatistics error_statistics(std::span<const double> errors);

enum class Alignment {
  kNone,       // compare poses as given
  kFirstPose,  // express the estimate relative to its first pose, anchored at the reference
};

// APE at each estimate pose whose time lies inside the reference (reference interpolated).
PoseErrors absolute_pose_error(const Trajectory& reference, const Trajectory& estimate, Alignment alignment);

// For each relation (t1, t2, Δ_ref) with both times inside the estimate: the error of
// Δ_est = est(t1)⁻¹ est(t2) against Δ_ref, i.e. Δ_ref⁻¹ Δ_est.
PoseErrors relation_error(const Trajectory& estimate, std::span<const Relation> relations);

// Reference relations over consecutive windows of `window` seconds of a trajectory (e.g. a
// ground truth), for relative-pose error where no .relations file exists.
std::vector<Relation> window_relations(const Trajectory& reference, double window);

}  // namespace locbench
