#pragma once
// Floor noise: the ground travel of a wheel differs from its rim travel U by δ ~ N(0, k²|U|)
// (eq. 4.16, after Chong & Kleeman). Drawn per physics step with variance k²|ΔU|, so over an
// encoder sample the variances add up to k²|U| for any step size.
#include <cmath>

#include "core/rng.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

class FloorNoise {
 public:
  FloorNoise(const FloorNoiseConfig& c, Rng left, Rng right)
      : k_left_(c.k_left), k_right_(c.k_right), left_(left), right_(right) {}

  double left(double travel) { return draw(k_left_, travel, left_); }
  double right(double travel) { return draw(k_right_, travel, right_); }

 private:
  static double draw(double k, double travel, Rng& rng) {
    if (k == 0.0 || travel == 0.0) return 0.0;
    return k * std::sqrt(std::abs(travel)) * rng.normal();
  }
  double k_left_, k_right_;
  Rng left_, right_;
};

}  // namespace locbench::sim
