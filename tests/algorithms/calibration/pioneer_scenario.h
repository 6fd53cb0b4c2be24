#pragma once
// The simulated robot of the ML calibration tests.
#include "core/units.h"
#include "datasets/sim/presets.h"

namespace locbench::calibration::test {

// A Pioneer-like robot (fine encoders) whose true wheels and wheelbase differ from the nominal
// ones, on a noisy floor (k = 0.002 √m per wheel), without slip, from the origin; no world, no
// laser and no odometry records (the encoders only).
inline sim::Scenario pioneer_on_a_noisy_floor() {
  sim::Scenario s = sim::preset("room_laser");
  s.world.kind = sim::WorldKind::kNone;
  s.laser.timing.enabled = false;
  s.odometry.timing.enabled = false;
  s.slip = {};
  s.floor = {0.002, 0.002};
  s.robot.actual = {mm(192.8), mm(194.1), mm(334.0)};
  s.start = Pose2(0.0, 0.0, 0.0);
  return s;
}

}  // namespace locbench::calibration::test
