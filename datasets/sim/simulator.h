#pragma once
// The simulator's entry point. A differential-drive robot is driven through the scenario's
// motion program with its true geometry while its software believes the nominal model; the
// result holds the log such a robot would write (ENCODER, ODOM, COMPASS, FLASER, TRUEPOS and
// PARAM records, see datasets/sim/README.md) and the ground truth behind it.
// Deterministic: the same scenario and seed give bit-identical results; each noise source
// draws from its own Rng::stream(seed, k), so enabling one sensor never changes another's noise.
#include <cstdint>

#include "datasets/sim/scenario.h"
#include "datasets/sim/simulation_result.h"

namespace locbench::sim {

// Throws UsageError for an invalid scenario, InputError for an unreadable world file.
SimulationResult simulate(const Scenario& scenario, std::uint64_t seed);

// Sub-stream indices of Rng::stream(seed, index), one per noise source.
enum class NoiseStream : std::uint64_t {
  kFloorLeft = 1,
  kFloorRight = 2,
  kSlip = 3,
  kEncoderClock = 4,
  kOdometryClock = 5,
  kCompassClock = 6,
  kCompass = 7,
  kLaserClock = 8,
  kLaser = 9,
  kMotionNoise = 10,
  kTruth = 11,
  kStall = 12,
};

}  // namespace locbench::sim
