#pragma once
// A second generator of logs with hidden effects, for testing the diagnosis against data it does
// not model: where hidden_effects.h perturbs a log through the diagnosis's own window model, this
// one simulates the physics. A unicycle robot receives a random velocity command (steps between
// speeds and turn rates, slew-limited); its drive follows the command through a first-order
// response (τ), scales it (velocity scale, a speed-dependent scale, turn-rate scale), stalls now
// and then (translation held at 0 for a random time while the command goes on) and adds
// process noise (normal per 100 ms block, or Student-t per 1 s block for heavy tails); everything is integrated
// at 1 kHz. The log records, as MRCLAM's and many ROS logs do:
//  - ODOM: the dead-reckoned command at `odom_rate_hz`, stamped on a clock offset from the
//    truth's by `odometry_time_offset` (any value, not a multiple of a sample period);
//  - TRUEPOS: the true pose at `truth_rate_hz` with white noise;
//  - COMPASS (optional): the true heading with noise, rounded to a lattice offset + k·step and
//    printed with `compass_decimals` decimals, as a logger writing "%.6f" would.
// The log's PARAM records declare the nominal model (no compass resolution): the effects stay
// hidden; the tests compare the diagnosis with `PhysicalEffects`.
#include <cstdint>

#include "core/log.h"

namespace locbench::sim {

struct PhysicalEffects {
  double velocity_scale = 1.0;  // true v = (velocity_scale + speed_slope·|v_cmd|)·v_drive
  double speed_slope = 0.0;     // [s/m]
  double turn_rate_scale = 1.0;
  double drive_tau = 0.0;             // first-order drive response [s]; 0 = instantaneous
  double odometry_time_offset = 0.0;  // ODOM logged time − true time [s]
  double heavy_tail_dof = 0.0;        // process noise Student-t per 1 s block; 0 = normal
  // Drive stalls: episodes start at `stall_rate` per second and stop the robot's translation for
  // a duration drawn uniformly in [½, 3⁄2]·`stall_duration` (the diagnosis models a fixed one).
  double stall_rate = 0.0;              // [1/s]
  double stall_duration = 0.0;          // [s], mean
  double compass_step = 0.0;            // compass lattice [rad]; 0 = continuous
  double compass_lattice_offset = 0.0;  // [rad]
  int compass_decimals = 6;
};

struct PhysicalOptions {
  double duration = 300.0;  // [s]
  double odom_rate_hz = 10.0;
  double truth_rate_hz = 10.0;
  double truth_noise_xy = 1e-3;       // [m]
  double truth_noise_theta = 1e-3;    // [rad]
  double process_noise_xy = 2e-3;     // 1σ displacement noise per √s [m/√s]
  double process_noise_theta = 2e-3;  // [rad/√s]
  bool compass = false;
  double compass_rate_hz = 10.0;
  double compass_noise = 0.0035;  // [rad] (0.2°)
};

// Throws UsageError for invalid effects or options (non-positive rates, duration, scales).
Log generate_physical_log(const PhysicalEffects& effects, std::uint64_t seed, const PhysicalOptions& options = {});

}  // namespace locbench::sim
