#pragma once
// Electronic compass (§3): absolute heading counter-clockwise from world +x,
// reading = quantize(θ + bias + Σ zone biases + N(0, σ²), resolution), wrapped to [−π, π).
// The thesis's Trilobot compass had a 2° resolution, so its readings are multiples of 2°.
#include <Eigen/Core>

#include "core/pose2.h"
#include "core/rng.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

// Nearest multiple of `resolution` (unchanged when resolution is 0).
double quantize(double value, double resolution);

struct CompassMeasurement {
  double heading = 0.0;      // the reading [rad]
  double disturbance = 0.0;  // sum of the biases of the zones the robot is in [rad]
};

class CompassModel {
 public:
  CompassModel(const CompassConfig& c, Rng rng) : config_(c), rng_(rng) {}

  // Total zone bias at a position.
  double disturbance(const Eigen::Vector2d& p) const;
  CompassMeasurement measure(const Pose2& truth);

 private:
  CompassConfig config_;
  Rng rng_;
};

}  // namespace locbench::sim
