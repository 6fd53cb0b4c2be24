#pragma once
// Wheel slip (§3.2): at most one wheel slips per encoder sample interval; the slipping wheel
// (left or right with equal probability) loses a fraction f ~ U[magnitude_min, magnitude_max]
// of its travel for the whole interval. Whether an interval has a slip is decided when it
// starts, with the profile of the leg running then (straight or on-the-spot turn; none while
// standing). Rates are per interval, or per metre of wheel travel: p = 1 − exp(−rate · d) with
// d the commanded mean wheel speed × the interval's length.
#include <optional>

#include "core/rng.h"
#include "datasets/sim/motion_program.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

enum class Side { kLeft, kRight };

struct ActiveSlip {
  Side wheel = Side::kLeft;
  double fraction = 0.0;
};

class SlipModel {
 public:
  SlipModel(const SlipConfig& c, Rng rng) : config_(c), rng_(rng) {}

  // Probability that an interval of `duration` seconds, started on `phase`, has a slip.
  double probability(MotionPhase phase, double wheel_speed, double duration) const;
  std::optional<ActiveSlip> start_interval(MotionPhase phase, double wheel_speed, double duration);

 private:
  SlipConfig config_;
  Rng rng_;
};

}  // namespace locbench::sim
