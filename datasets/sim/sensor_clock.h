#pragma once
// When a sensor measures: instants k/rate (+ jitter), rounded to the physics step, strictly
// increasing. Generated one at a time so runs of any length need no precomputation.
#include <cstdint>

#include "core/rng.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

class SensorClock {
 public:
  // A disabled clock never fires. rate ≤ 0 (with enabled) fires at every physics step.
  SensorClock(const SensorTiming& timing, double step, Rng rng);

  bool enabled() const { return enabled_; }
  // Physics step index of the next measurement.
  std::int64_t next_step() const { return next_; }
  // Moves to the following measurement instant.
  void advance();

 private:
  std::int64_t instant(std::int64_t k);

  bool enabled_;
  double rate_;
  double jitter_;
  double step_;
  Rng rng_;
  std::int64_t k_ = 0;
  std::int64_t next_ = 0;
};

}  // namespace locbench::sim
