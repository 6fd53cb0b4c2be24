#pragma once
// UMBmark experiments for the tests of the classic and the improved method and of their shared
// input checks: the square, the robot its software believed it drove, the counts of a leg, the runs.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/umbmark_measurements.h"

namespace locbench::testing {

// The `runs` on a square of side `side` [m] of a robot believed to have the wheels `nominal` and
// the encoders `encoder`; `leg_ticks` counts logged on each wheel along one straight leg (0: none).
inline UmbmarkInput umbmark_square(double side, const WheelGeometry& nominal, const EncoderSpec& encoder,
                                   std::int64_t leg_ticks, std::vector<UmbmarkReturn> runs) {
  UmbmarkInput in;
  in.side_length = side;
  in.nominal = nominal;
  in.encoder = encoder;
  in.leg_ticks_left = leg_ticks;
  in.leg_ticks_right = leg_ticks;
  in.runs = std::move(runs);
  return in;
}

// A LabMate-like robot on Borenstein's 4 m square: D_n = 150 mm, B = 340 mm, n = 1, C_e = 1000
// counts per revolution.
inline UmbmarkInput labmate_square(std::int64_t leg_ticks, std::vector<UmbmarkReturn> runs) {
  return umbmark_square(4.0, {0.15, 0.15, 0.34}, {1.0, 1000.0}, leg_ticks, std::move(runs));
}

}  // namespace locbench::testing
