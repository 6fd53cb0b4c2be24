#pragma once
// Independent checks of a fitted distance or turn scale, computed another way than the
// diagnosis's likelihood: over the same windows, the ratio of the reference's summed path length
// to the odometry's, and least-squares slopes through the origin of the reference's window length
// on the odometry's (and of its turn on the odometry's turn). No noise model, no selection: what
// a user would compute by hand to see whether a reported scale is believable.
#include <cstddef>

#include "algorithms/diagnosis/motion_windows.h"

namespace locbench::diagnosis {

struct ScaleChecks {
  double path_length_ratio = 0.0;  // Σ|reference translation| / Σ|odometry distance|
  double ls_velocity_scale = 0.0;  // Σ ref·odo / Σ odo² of window lengths
  double ls_turn_scale = 0.0;      // Σ Δθ_ref·Δθ_odo / Σ Δθ_odo²
  std::size_t windows = 0;
};

// `time_offset`: the odometry's logged time minus the reference's (e.g. the diagnosis's estimate;
// ignored for relations). Windows the shifted reference does not cover are skipped.
ScaleChecks scale_checks(const MotionData& d, double time_offset);

}  // namespace locbench::diagnosis
