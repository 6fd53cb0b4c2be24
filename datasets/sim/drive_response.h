#pragma once
// How a robot's drive turns a commanded body velocity into the velocity it really moves at
// (replayed motion only, motion.kind = "replay"): a first-order lag of time constant τ on both
// v and ω, then a speed-dependent velocity scale and a turn-rate scale and bias:
//   τ·dv_l/dt = v_cmd − v_l,   τ·dω_l/dt = ω_cmd − ω_l         (τ = 0: v_l = v_cmd, ω_l = ω_cmd)
//   v = (velocity_scale + speed_slope·|v_l|)·v_l,   ω = turn_rate_scale·ω_l + turn_rate_bias.
// Stalls: episodes start at `stall_rate` per second (a Poisson process) and hold the forward
// velocity at 0 for `stall_duration` seconds while the log keeps the command.
// These are the diagnosis causes drive_response, velocity_scale, speed_dependent_scale,
// drive_stall, turn_rate_scale and turn_rate_bias (algorithms/diagnosis/) run forwards.
#include <cmath>

namespace locbench::sim {

struct DriveResponse {
  double time_constant = 0.0;    // τ [s]; 0 = the drive follows the command at once
  double velocity_scale = 1.0;   // true v / commanded v at zero speed
  double speed_slope = 0.0;      // change of that scale per m/s of commanded speed [s/m]
  double turn_rate_scale = 1.0;  // true ω / commanded ω
  double turn_rate_bias = 0.0;   // [rad/s], added whether or not the robot moves
  double stall_rate = 0.0;       // stall episodes per second
  double stall_duration = 0.0;   // [s] each

  bool is_identity() const {
    return time_constant == 0.0 && velocity_scale == 1.0 && speed_slope == 0.0 && turn_rate_scale == 1.0 &&
           turn_rate_bias == 0.0 && stall_rate == 0.0;
  }
};

struct BodyVelocity {
  double v = 0.0;      // forward [m/s]
  double omega = 0.0;  // counter-clockwise [rad/s]
};

// The lag's state, advanced by exact discretisation over a step dt with the command held.
class DriveLag {
 public:
  explicit DriveLag(double time_constant) : tau_(time_constant) {}
  BodyVelocity step(BodyVelocity command, double dt) {
    if (tau_ <= 0.0) return state_ = command;
    const double a = 1.0 - std::exp(-dt / tau_);
    state_.v += a * (command.v - state_.v);
    state_.omega += a * (command.omega - state_.omega);
    return state_;
  }

 private:
  double tau_;
  BodyVelocity state_;
};

// The scales and bias applied to the lagged command.
inline BodyVelocity apply_response(const DriveResponse& r, BodyVelocity lagged) {
  return {(r.velocity_scale + r.speed_slope * std::abs(lagged.v)) * lagged.v,
          r.turn_rate_scale * lagged.omega + r.turn_rate_bias};
}

}  // namespace locbench::sim
