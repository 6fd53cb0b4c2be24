#include "datasets/sim/umbmark_input.h"

#include "datasets/sim/motion_program.h"

namespace locbench::sim {

std::vector<UmbmarkReturn> umbmark_returns(const std::vector<UmbmarkRun>& runs) {
  std::vector<UmbmarkReturn> out;
  out.reserve(runs.size());
  for (const auto& r : runs) {
    out.push_back(
        {r.direction == Direction::kClockwise ? UmbmarkDirection::kClockwise : UmbmarkDirection::kCounterClockwise,
         r.error.x(), r.error.y()});
  }
  return out;
}

UmbmarkInput umbmark_input(const Scenario& scenario, const std::vector<UmbmarkRun>& runs, double tape_measure_scale) {
  UmbmarkInput in;
  in.side_length = scenario.motion.side;
  in.nominal = scenario.robot.nominal;
  in.encoder = scenario.robot.encoder;
  in.tape_measure_scale = tape_measure_scale;
  const WheelTicks leg =
      straight_ticks(scenario.motion.side, scenario.robot.params().nominal_model(), scenario.drive.equal_wheel_ticks);
  in.leg_ticks_left = leg.left;
  in.leg_ticks_right = leg.right;
  in.runs = umbmark_returns(runs);
  return in;
}

}  // namespace locbench::sim
