#pragma once
// Simulated UMBmark runs → the measured data a person would write down (UmbmarkInput), so the
// calibration methods can be run on simulated experiments exactly as on real ones.
#include <vector>

#include "core/umbmark_measurements.h"
#include "datasets/sim/scenario.h"
#include "datasets/sim/simulation_result.h"

namespace locbench::sim {

// The return errors (x, y) of each run, direction converted; the heading error is dropped
// (UMBmark does not measure it).
std::vector<UmbmarkReturn> umbmark_returns(const std::vector<UmbmarkRun>& runs);

// The measured data of a simulated UMBmark experiment: side, the scenario's nominal geometry and
// encoder, `tape_measure_scale` as given (E_s; pass the true E_o for a perfect tape, 1 for none),
// and the counts N_L, N_R the robot logged on a straight leg — the counts it was commanded from
// its nominal model (`straight_ticks`), which the servo executes exactly.
UmbmarkInput umbmark_input(const Scenario& scenario, const std::vector<UmbmarkRun>& runs,
                           double tape_measure_scale = 1.0);

}  // namespace locbench::sim
