#pragma once
#include <cmath>

#include "core/units.h"

namespace locbench {

// Wraps an angle to [-π, π).
inline double wrap_angle(double a) {
  if (a >= -kPi && a < kPi) return a;
  double w = std::fmod(a + kPi, 2.0 * kPi);
  if (w < 0.0) w += 2.0 * kPi;
  return w - kPi;
}

// Smallest signed difference a − b, wrapped to [-π, π).
inline double angle_diff(double a, double b) { return wrap_angle(a - b); }

}  // namespace locbench
