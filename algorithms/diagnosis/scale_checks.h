#pragma once
// Independent checks of a fitted distance or turn scale, computed another way than the
// diagnosis's likelihood: over the same windows, the ratio of the reference's summed path length
// to the odometry's, and least-squares slopes through the origin of the reference's window length
// on the odometry's (and of its turn on the odometry's turn). No noise model, no selection: what
// a user would compute by hand to see whether a reported scale is believable.
#include <cstddef>
#include <string>
#include <vector>

#include "algorithms/diagnosis/motion_windows.h"

namespace locbench::diagnosis {

struct ScaleChecks {
  double path_length_ratio = 0.0;  // Σ|reference translation| / Σ|odometry distance|
  double ls_velocity_scale = 0.0;  // Σ ref·odo / Σ odo² of window lengths
  double ls_turn_scale = 0.0;      // Σ Δθ_ref·Δθ_odo / Σ Δθ_odo²
  // Median over windows of |reference| / |odometry| (odometry longer than 2 cm): far from the
  // path-length ratio when the per-window ratio is skewed (windows that lose distance).
  double median_window_ratio = 0.0;
  std::size_t windows = 0;
};

// `time_offset`: the odometry's logged time minus the reference's (e.g. the diagnosis's estimate;
// ignored for relations). Windows the shifted reference does not cover are skipped.
ScaleChecks scale_checks(const MotionData& d, double time_offset);

// The velocity scale a diagnosis kept (velocity_scale; speed_dependent_scale at the logged mean
// speed is not comparable and gives none) set beside the checks: empty when the scale's 95%
// interval meets the checks' range widened by `tolerance`, else one sentence that says how they
// disagree and, when the per-window ratio is skewed, why.
// `what` names the scale ("velocity scale", or drive_stall's implied mean distance scale).
std::string scale_disagreement(const std::string& log, double value, double lo, double hi, const ScaleChecks& c,
                               double tolerance = 0.02, const std::string& what = "velocity scale");

}  // namespace locbench::diagnosis
