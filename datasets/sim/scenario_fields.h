#pragma once
// The scenario's flat option groups, each field stated once (name, unit, allowed range,
// meaning): scenario_json.cpp reads and writes them through these visitors and scenario.cpp
// checks their ranges with validate_fields (core/option_fields.h). Groups whose rules
// depend on other fields (sensor timing only when enabled, slip rate by its unit) keep those
// rules in scenario.cpp.
#include "core/option_fields.h"
#include "core/robot_params.h"
#include "datasets/sim/drive_response.h"
#include "datasets/sim/motion_noise.h"
#include "datasets/sim/scenario.h"

namespace locbench {

template <class V>
void visit_fields(V& v, WheelGeometry& g) {
  v.field("diameter_left", g.diameter_left, "m", positive(), "D_L");
  v.field("diameter_right", g.diameter_right, "m", positive(), "D_R");
  v.field("wheelbase", g.wheelbase, "m", positive(), "B");
}

}  // namespace locbench

namespace locbench::sim {

template <class V>
void visit_fields(V& v, SensorTiming& t) {
  v.flag("enabled", t.enabled, "the sensor is logged");
  v.field("rate", t.rate, "Hz", positive(), "records per second (when enabled)");
  v.field("latency", t.latency, "s", any_finite(), "logged time − true measurement time");
  v.field("jitter", t.jitter, "s", non_negative(), "σ of each instant around k/rate");
}

template <class V>
void visit_fields(V& v, SlipProfile& p) {
  v.field("rate", p.rate, "", non_negative(), "per sample (a probability) or per metre, by slip.unit");
  v.field("magnitude_min", p.magnitude_min, "", closed(0.0, 1.0), "fraction of the wheel's travel lost");
  v.field("magnitude_max", p.magnitude_max, "", closed(0.0, 1.0), "≥ magnitude_min");
}

template <class V>
void visit_fields(V& v, DriveResponse& r) {
  v.field("time_constant", r.time_constant, "s", non_negative(), "τ; 0 = the drive follows at once");
  v.field("velocity_scale", r.velocity_scale, "", any_finite(), "true v / commanded v at zero speed");
  v.field("speed_slope", r.speed_slope, "s/m", any_finite(), "change of that scale per m/s");
  v.field("turn_rate_scale", r.turn_rate_scale, "", any_finite(), "true ω / commanded ω");
  v.field("turn_rate_bias", r.turn_rate_bias, "rad/s", any_finite(), "added whether or not the robot moves");
  v.field("stall_rate", r.stall_rate, "1/s", non_negative(), "stall episodes per second");
  v.field("stall_duration", r.stall_duration, "s", non_negative(), "each");
}

template <class V>
void visit_fields(V& v, MotionNoiseConfig& n) {
  v.field("window", n.window, "s", positive(), "noise window");
  v.field("sigma_along", n.sigma_along, "m", non_negative(), "per window");
  v.field("sigma_left", n.sigma_left, "m", non_negative(), "per window");
  v.field("sigma_heading", n.sigma_heading, "rad", non_negative(), "per window");
  v.field("dof", n.dof, "", non_negative(), "Student-t degrees of freedom; 0 = Gaussian");
}

}  // namespace locbench::sim
