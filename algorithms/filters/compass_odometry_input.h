#pragma once
// Turns ENCODER and COMPASS records into the per-sample inputs of the compass EKFs: the wheel
// travel between consecutive encoder samples (nominal model) and the compass heading taken
// closest in time to the later sample, if one lies within `max_offset` seconds.
#include <optional>
#include <span>
#include <vector>

#include "core/diff_drive_odometry.h"
#include "core/robot_params.h"
#include "core/sensor_data.h"

namespace locbench::filters {

struct CompassOdometrySample {
  double t = 0.0;                 // time of the later encoder sample [s]
  std::size_t encoder_index = 0;  // index of that sample in the encoder records (>= 1)
  WheelDisplacement u;            // U_L, U_R [m]
  std::optional<double> compass;  // heading [rad]
};

// One sample per encoder record after the first. Each compass reading is used at most once
// (the nearest one within max_offset, searched forward in time order). Throws
// std::invalid_argument when max_offset < 0.
std::vector<CompassOdometrySample> pair_encoder_compass(std::span<const EncoderReading> encoders,
                                                        std::span<const CompassReading> compass,
                                                        const NominalModel& model, double max_offset);

}  // namespace locbench::filters
