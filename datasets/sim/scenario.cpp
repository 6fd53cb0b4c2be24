#include "datasets/sim/scenario.h"

#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/units.h"
#include "datasets/sim/scenario_fields.h"

namespace locbench::sim {

bool DisturbanceZone::contains(const Eigen::Vector2d& p) const {
  if (shape == Shape::kCircle) return (p - center).norm() <= radius;
  return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
}

namespace {

void require(bool ok, const std::string& field, const char* rule) {
  if (!ok) throw UsageError("scenario: " + field + " must be " + rule);
}
void positive(double v, const std::string& field) { require(std::isfinite(v) && v > 0.0, field, "> 0"); }
void non_negative(double v, const std::string& field) { require(std::isfinite(v) && v >= 0.0, field, ">= 0"); }
void probability(double v, const std::string& field) {
  require(std::isfinite(v) && v >= 0.0 && v <= 1.0, field, "in [0, 1]");
}
void finite(double v, const std::string& field) { require(std::isfinite(v), field, "finite"); }

void check_timing(const SensorTiming& t, const std::string& field) {
  if (!t.enabled) return;
  positive(t.rate, field + ".rate");
  finite(t.latency, field + ".latency");
  non_negative(t.jitter, field + ".jitter");
}

void check_slip(const SlipProfile& p, SlipRateUnit unit, const std::string& field) {
  if (unit == SlipRateUnit::kPerSample) {
    probability(p.rate, field + ".rate");
  } else {
    non_negative(p.rate, field + ".rate");
  }
  probability(p.magnitude_min, field + ".magnitude_min");
  probability(p.magnitude_max, field + ".magnitude_max");
  require(p.magnitude_min <= p.magnitude_max, field + ".magnitude_min", "<= magnitude_max");
}

void validate_replay(const Scenario& s) {
  const auto& c = s.motion.commands;
  require(c.size() >= 2, "motion.commands", "at least 2 commands");
  const double latency = s.odometry.timing.enabled ? s.odometry.timing.latency : s.encoders.timing.latency;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::string at = "motion.commands[" + std::to_string(i) + "]";
    finite(c[i].t, at + "[0]");
    finite(c[i].v, at + "[1]");
    finite(c[i].omega, at + "[2]");
    if (i > 0) require(c[i].t > c[i - 1].t, at + "[0]", "greater than the previous command's time");
  }
  require(c.front().t - latency >= 0.0, "motion.commands[0][0] − the odometry latency",
          ">= 0 (the robot cannot execute a command before the simulation starts)");
  validate_fields(s.drive.response, "scenario: drive.response");
}

}  // namespace

void validate(const Scenario& s) {
  if (s.world.kind == WorldKind::kCorridor) {
    positive(s.world.corridor_length, "world.corridor_length");
    positive(s.world.corridor_width, "world.corridor_width");
  }
  if (s.world.kind == WorldKind::kFile) require(!s.world.file.empty(), "world.file", "set");
  finite(s.start.x, "start[0]");
  finite(s.start.y, "start[1]");
  finite(s.start.theta, "start[2]");

  validate_fields(s.robot.nominal, "scenario: robot.nominal");
  validate_fields(s.robot.actual, "scenario: robot.actual");
  positive(s.robot.encoder.gear_ratio, "robot.encoder.gear_ratio");
  positive(s.robot.encoder.counts_per_rev, "robot.encoder.counts_per_rev");

  positive(s.drive.speed, "drive.speed");
  positive(s.drive.turn_rate, "drive.turn_rate");
  non_negative(s.drive.pause, "drive.pause");

  switch (s.motion.kind) {
    case MotionKind::kStraight: finite(s.motion.distance, "motion.distance"); break;
    case MotionKind::kUmbmark:
      positive(s.motion.side, "motion.side");
      require(s.motion.runs >= 1, "motion.runs", ">= 1");
      break;
    case MotionKind::kWaypoints: require(!s.motion.waypoints.empty(), "motion.waypoints", "non-empty"); break;
    case MotionKind::kReplay: validate_replay(s); break;
  }

  positive(s.physics.step, "physics.step");
  require(s.physics.step <= 0.1, "physics.step", "<= 0.1 s");
  non_negative(s.physics.trajectory_rate, "physics.trajectory_rate");

  validate_fields(s.motion_noise, "scenario: motion_noise");
  non_negative(s.floor.k_left, "floor.k_left");
  non_negative(s.floor.k_right, "floor.k_right");
  check_slip(s.slip.straight, s.slip.unit, "slip.straight");
  check_slip(s.slip.turn, s.slip.unit, "slip.turn");

  check_timing(s.encoders.timing, "encoders");
  check_timing(s.odometry.timing, "odometry");
  check_timing(s.compass.timing, "compass");
  non_negative(s.compass.resolution, "compass.resolution");
  non_negative(s.compass.noise, "compass.noise");
  finite(s.compass.bias, "compass.bias");
  for (const auto& z : s.compass.zones) {
    finite(z.bias, "compass.zones[].bias");
    if (z.shape == DisturbanceZone::Shape::kCircle) non_negative(z.radius, "compass.zones[].radius");
  }

  check_timing(s.laser.timing, "laser");
  require(s.laser.beams >= 1, "laser.beams", ">= 1");
  finite(s.laser.first_bearing, "laser.first_bearing");
  finite(s.laser.last_bearing, "laser.last_bearing");
  require(s.laser.first_bearing <= s.laser.last_bearing && s.laser.last_bearing - s.laser.first_bearing <= 2.0 * kPi,
          "laser.last_bearing", ">= laser.first_bearing and at most 2π [rad] beyond it");
  require(std::abs(s.laser.first_bearing + s.laser.last_bearing) <= 1e-9, "laser.first_bearing",
          "-laser.last_bearing (a field of view centred on the laser's heading, as a CARMEN log declares it; "
          "aim the laser with laser.mount.theta)");
  positive(s.laser.max_range, "laser.max_range");
  non_negative(s.laser.noise, "laser.noise");
  finite(s.laser.range_offset, "laser.range_offset");
  positive(s.laser.range_scale, "laser.range_scale");
  probability(s.laser.dropout, "laser.dropout");
  probability(s.laser.spurious, "laser.spurious");
  require(s.laser.dropout + s.laser.spurious <= 1.0, "laser.dropout + laser.spurious", "<= 1");

  non_negative(s.truth.rate, "truth.rate");
  non_negative(s.truth.noise_xy, "truth.noise_xy");
  non_negative(s.truth.noise_theta, "truth.noise_theta");
}

}  // namespace locbench::sim
