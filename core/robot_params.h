#pragma once
// Differential-drive robot geometry: what the robot's software believes (nominal) and what
// the robot really is (actual). All lengths in metres.
#include <cmath>

#include "core/units.h"

namespace locbench {

struct WheelGeometry {
  double diameter_left = 0.0;   // D_L [m]
  double diameter_right = 0.0;  // D_R [m]
  double wheelbase = 0.0;       // B [m]

  double mean_diameter() const { return 0.5 * (diameter_left + diameter_right); }
};

struct EncoderSpec {
  double gear_ratio = 1.0;      // n
  double counts_per_rev = 1.0;  // C_e, encoder counts per motor revolution
  // Encoder counts per wheel revolution, n·C_e.
  double counts_per_wheel_rev() const { return gear_ratio * counts_per_rev; }
};

// The odometry model a robot's software uses (and logs as PARAM records).
struct NominalModel {
  double meters_per_tick_left = 0.0;   // c_L [m/tick]
  double meters_per_tick_right = 0.0;  // c_R [m/tick]
  double wheelbase = 0.0;              // B [m]
};

struct RobotParams {
  WheelGeometry nominal;
  WheelGeometry actual;
  EncoderSpec encoder;

  // Metres per tick for a wheel of diameter d: c = πd / (n C_e) (eq. 2.24–2.25 inverted).
  double meters_per_tick(double diameter) const { return kPi * diameter / encoder.counts_per_wheel_rev(); }
  NominalModel nominal_model() const {
    return {meters_per_tick(nominal.diameter_left), meters_per_tick(nominal.diameter_right), nominal.wheelbase};
  }
  NominalModel actual_model() const {
    return {meters_per_tick(actual.diameter_left), meters_per_tick(actual.diameter_right), actual.wheelbase};
  }
  // E_d = D_R/D_L of the actual wheels (eq. 2.1).
  double E_d() const { return actual.diameter_right / actual.diameter_left; }
  // E_b = B_actual / B_nominal (eq. 2.2).
  double E_b() const { return actual.wheelbase / nominal.wheelbase; }
  // E_o = D_a / D_n, mean actual over mean nominal diameter (eq. 2.15, "E_s" in UMBmark).
  double E_o() const { return actual.mean_diameter() / nominal.mean_diameter(); }
};

}  // namespace locbench
