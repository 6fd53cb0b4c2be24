#include "datasets/sim/simulator.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <optional>

#include "core/angle.h"
#include "core/diff_drive_odometry.h"
#include "core/units.h"
#include "datasets/sim/compass_model.h"
#include "datasets/sim/floor_noise.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/sensor_clock.h"
#include "datasets/sim/wheel_encoder_model.h"
#include "datasets/sim/worlds.h"

namespace locbench::sim {
namespace {

Rng stream(std::uint64_t seed, NoiseStream s) { return Rng::stream(seed, static_cast<std::uint64_t>(s)); }

SensorTiming every(double rate) { return SensorTiming{true, rate, 0.0, 0.0}; }

std::string number(double v) { return fmt::format("{}", v); }

// PARAM values are single words in CARMEN logs: whitespace becomes '_', empty becomes '-'.
std::string word(std::string s) {
  for (char& c : s) {
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  }
  return s.empty() ? "-" : s;
}

class Simulation {
 public:
  Simulation(const Scenario& s, std::uint64_t seed)
      : sc_(s),
        dt_(s.physics.step),
        robot_(s.robot.params()),
        nominal_(robot_.nominal_model()),
        program_(build_program(s.motion, s.drive, s.start)),
        floor_(s.floor, stream(seed, NoiseStream::kFloorLeft), stream(seed, NoiseStream::kFloorRight)),
        slip_(s.slip, stream(seed, NoiseStream::kSlip)),
        compass_(s.compass, stream(seed, NoiseStream::kCompass)),
        motion_noise_(s.motion_noise, stream(seed, NoiseStream::kMotionNoise)),
        truth_noise_(stream(seed, NoiseStream::kTruth)),
        stall_(stream(seed, NoiseStream::kStall)),
        replay_(s.motion.kind == MotionKind::kReplay),
        lag_(s.drive.response.time_constant),
        // The encoder clock is also the slip/noise sample grid; without encoders it is 10 Hz.
        grid_(s.encoders.timing.enabled ? s.encoders.timing : every(10.0), dt_,
              stream(seed, NoiseStream::kEncoderClock)),
        odometry_clock_(s.odometry.timing, dt_, stream(seed, NoiseStream::kOdometryClock)),
        compass_clock_(s.compass.timing, dt_, stream(seed, NoiseStream::kCompassClock)),
        laser_clock_(s.laser.timing, dt_, stream(seed, NoiseStream::kLaserClock)),
        truth_clock_(SensorTiming{s.truth.rate > 0.0, s.truth.rate, 0.0, 0.0}, dt_, Rng(0)),
        trajectory_clock_(every(s.physics.trajectory_rate), dt_, Rng(0)) {
    result_.scenario = s;
    result_.seed = seed;
    result_.robot = robot_;
    result_.world = build_world(s.world);
    if (s.laser.timing.enabled) {
      laser_.emplace(s.laser, result_.world, stream(seed, NoiseStream::kLaser));
    }
    truth_ = belief_ = s.start;
    left_.meters_per_tick = robot_.meters_per_tick(robot_.actual.diameter_left);
    right_.meters_per_tick = robot_.meters_per_tick(robot_.actual.diameter_right);
    write_params(seed);
  }

  SimulationResult run() {
    if (replay_) return run_replay();
    emit();
    while (ensure_leg()) {
      if (interval_pending_) start_interval();
      step();
      emit();
      if (leg_i_ == leg_.steps) has_leg_ = false;
    }
    if (active_) close_slip_event(now());
    result_.duration = now();
    return std::move(result_);
  }

  // Replayed motion: command i holds from true time t_i − latency; its odometry record (ODOM
  // with the command's pose, v, ω, and/or ENCODER with the counts reached) is stamped t_i.
  SimulationResult run_replay() {
    const auto& cmds = sc_.motion.commands;
    const bool odom = sc_.odometry.timing.enabled;
    const double latency = odom ? sc_.odometry.timing.latency : sc_.encoders.timing.latency;
    // Wheels start half a tick into a count, so that summed fractional increments of a whole
    // number of ticks never fall just short of it.
    left_.q = right_.q = 0.5;
    Pose2 logged = sc_.start;  // the command sequence integrated (midpoint rule), as logged
    std::size_t next = 0;      // next command whose record is due
    const auto record_due = [&] {
      while (next < cmds.size() && cmds[next].t - latency <= now() + 0.5 * dt_) {
        if (next > 0) {
          const ReplayCommand& c = cmds[next - 1];
          const double span = cmds[next].t - c.t;
          const double dth = c.omega * span, mid = logged.theta + 0.5 * dth;
          logged =
              Pose2(logged.x + c.v * span * std::cos(mid), logged.y + c.v * span * std::sin(mid), logged.theta + dth);
        }
        if (odom) result_.log.odometry.push_back({cmds[next].t, logged, cmds[next].v, cmds[next].omega});
        if (sc_.encoders.timing.enabled) {
          result_.log.encoders.push_back({cmds[next].t, left_.count(), right_.count()});
        }
        ++next;
      }
    };
    record_due();
    emit();
    const auto end = static_cast<std::int64_t>(std::llround((cmds.back().t - latency) / dt_));
    std::size_t in_force = 0;
    while (n_ < end) {
      in_force = replay_command_index(cmds, now() + latency + 0.5 * dt_, in_force);
      const BodyVelocity command =
          in_force == 0 ? BodyVelocity{} : BodyVelocity{cmds[in_force - 1].v, cmds[in_force - 1].omega};
      BodyVelocity drive = apply_response(sc_.drive.response, lag_.step(command, dt_));
      const DriveResponse& response = sc_.drive.response;
      if (response.stall_rate > 0.0 && now() >= stall_until_ &&
          stall_.bernoulli(-std::expm1(-response.stall_rate * dt_))) {
        stall_until_ = now() + response.stall_duration;
      }
      if (now() < stall_until_) drive.v = 0.0;
      const WheelSpeeds u = replay_wheel_speeds(drive, nominal_.wheelbase);
      leg_.phase = replay_phase(u);
      leg_.wheel_speed = 0.5 * (std::abs(u.left) + std::abs(u.right));
      if (interval_pending_) start_interval();
      ++n_;
      advance(left_.q + u.left * dt_ / nominal_.meters_per_tick_left,
              right_.q + u.right * dt_ / nominal_.meters_per_tick_right);
      record_due();
      emit();
    }
    if (active_) close_slip_event(now());
    result_.duration = now();
    return std::move(result_);
  }

 private:
  // n·dt, computed as n / (steps per second) when that is a whole number, so that times print
  // as written (0.954, not 0.9540000000000001).
  double now() const {
    const double per_second = std::round(1.0 / dt_);
    return std::abs(per_second * dt_ - 1.0) < 1e-12 ? static_cast<double>(n_) / per_second
                                                    : static_cast<double>(n_) * dt_;
  }

  void write_params(std::uint64_t seed) {
    Log& log = result_.log;
    log.name = "sim/" + sc_.name;
    log.source = "simulated";
    auto& p = log.params;
    p[kParamMetersPerTickLeft] = number(nominal_.meters_per_tick_left);
    p[kParamMetersPerTickRight] = number(nominal_.meters_per_tick_right);
    p[kParamWheelbase] = number(nominal_.wheelbase);
    p["robot_wheel_diameter_left"] = number(robot_.nominal.diameter_left);
    p["robot_wheel_diameter_right"] = number(robot_.nominal.diameter_right);
    p["robot_encoder_counts_per_rev"] = number(robot_.encoder.counts_per_wheel_rev());
    p["sim_scenario"] = word(sc_.name);
    p["sim_seed"] = std::to_string(seed);
    p["sim_world"] = word(result_.world.name);
    if (sc_.compass.timing.enabled) p["compass_resolution"] = number(sc_.compass.resolution);
    if (sc_.laser.timing.enabled) {
      p["robot_frontlaser_offset"] = number(sc_.laser.mount.x);
      p["robot_frontlaser_side_offset"] = number(sc_.laser.mount.y);
      p["robot_frontlaser_angular_offset"] = number(sc_.laser.mount.theta);
      p["laser_front_laser_max_range"] = number(sc_.laser.max_range);
      declare_laser_span(p);
    }
  }

  // Bearings other than the FLASER convention (an odd count over −90°…90°, or one beam at −90°;
  // an even count such as 180 or 360 is not) are declared as a field of view [deg], so that the
  // CARMEN log reads back with the bearings simulated. The span is centred (validate()).
  void declare_laser_span(std::map<std::string, std::string>& p) const {
    const auto& l = sc_.laser;
    const bool from_minus_90 = std::abs(l.first_bearing + 0.5 * kPi) < 1e-12;
    const bool flaser =
        from_minus_90 && (l.beams == 1 || (l.beams % 2 == 1 && std::abs(l.last_bearing - 0.5 * kPi) < 1e-12));
    if (flaser) return;
    if (l.beams == 1 && l.first_bearing == 0.0) {
      p["laser_front_laser_resolution"] = "1";  // one beam straight ahead: centred steps
    } else {
      p["laser_front_laser_fov"] = number(to_deg(l.last_bearing - l.first_bearing));
    }
  }

  // Makes the next leg current, carrying out the instantaneous instructions on the way.
  bool ensure_leg() {
    using K = Instruction::Kind;
    while (!has_leg_) {
      if (pc_ >= program_.size()) return false;
      const Instruction in = resolve(program_[pc_++], belief_);
      if (in.kind == K::kReset) {
        truth_ = in.pose;
        belief_ = in.pose;
      } else if (in.kind == K::kRunBegin) {
        UmbmarkRun r;
        r.direction = in.direction;
        r.run = in.run;
        r.t_start = now();
        r.start = truth_;
        run_belief_start_ = belief_;
        result_.umbmark_runs.push_back(r);
      } else if (in.kind == K::kRunEnd) {
        end_run();
      } else {
        leg_ = plan_leg(in, nominal_, sc_.drive, dt_);
        if (leg_.steps > 0) {
          has_leg_ = true;
          leg_i_ = 0;
          leg_q0_left_ = left_.q;
          leg_q0_right_ = right_.q;
        }
      }
    }
    return true;
  }

  void end_run() {
    UmbmarkRun& r = result_.umbmark_runs.back();
    r.t_end = now();
    r.true_end = truth_;
    r.odometry_end = belief_;
    const Pose2 t = between(r.start, truth_);
    const Pose2 o = between(run_belief_start_, belief_);
    r.error = {t.x - o.x, t.y - o.y, angle_diff(t.theta, o.theta)};
  }

  // Decides whether the encoder sample interval that starts now has a slip (slip_model.h).
  void start_interval() {
    interval_pending_ = false;
    const MotionPhase phase = has_leg_ ? leg_.phase : MotionPhase::kIdle;
    const double duration = static_cast<double>(grid_.next_step() - n_) * dt_;  // [s]
    active_ = slip_.start_interval(phase, leg_.wheel_speed, duration);
    if (active_) {
      event_ = SlipEvent{};
      event_.sample = result_.wheel_samples.size() - 1;
      event_.t_start = now();
      event_.wheel = active_->wheel;
      event_.phase = phase;
      event_.fraction = active_->fraction;
    }
  }

  void close_slip_event(double t) {
    event_.t_end = t;
    result_.slips.push_back(event_);
    active_.reset();
  }

  // Moves one wheel to its new rim position; returns its ground travel in this step.
  double move_wheel(Wheel& w, double q, Side side) {
    const double rim = (q - w.q) * w.meters_per_tick;
    w.q = q;
    if (rim == 0.0) return 0.0;
    double lost = 0.0;
    if (active_ && active_->wheel == side) {
      lost = active_->fraction * rim;
      w.slip += lost;
      event_.lost += lost;
    }
    const double noise = side == Side::kLeft ? floor_.left(rim) : floor_.right(rim);
    const double ground = rim - lost + noise;
    w.ground += ground;
    return ground;
  }

  // One physics step of the current leg: wheels, true pose, the robot's own odometry.
  void step() {
    ++leg_i_;
    ++n_;
    if (leg_.phase == MotionPhase::kIdle) {
      add_motion_noise();
      return;
    }
    const auto at = [&](double q0, std::int64_t ticks) {
      return q0 + static_cast<double>(ticks * leg_i_) / static_cast<double>(leg_.steps);
    };
    advance(at(leg_q0_left_, leg_.ticks.left), at(leg_q0_right_, leg_.ticks.right));
  }

  // The motion noise of the step just taken (motion_noise.h), in the robot frame.
  void add_motion_noise() {
    if (sc_.motion_noise.enabled()) truth_ = truth_ * motion_noise_.step(now() - dt_, dt_);
  }

  // Moves both wheels to their new rim positions [ticks]; moves the true pose; the firmware
  // integrates the count changes.
  void advance(double q_left, double q_right) {
    const double gl = move_wheel(left_, q_left, Side::kLeft);
    const double gr = move_wheel(right_, q_right, Side::kRight);
    truth_ = exact_arc_step(truth_, {gl, gr}, robot_.actual.wheelbase);
    add_motion_noise();

    // The robot's firmware integrates every count change with the nominal model (eq. 1.1–1.3).
    const std::int64_t cl = left_.count(), cr = right_.count();
    if (cl != fw_left_ || cr != fw_right_) {
      const WheelDisplacement u = displacement_from_ticks(nominal_, cl - fw_left_, cr - fw_right_);
      belief_ = odometry_step(belief_, u, nominal_.wheelbase);
      const BodyIncrement b = body_increment(u, nominal_.wheelbase);
      odo_distance_ += b.distance;
      odo_rotation_ += b.rotation;
      fw_left_ = cl;
      fw_right_ = cr;
    }
  }

  // Records every measurement due at the current step.
  void emit() {
    const double t = now();
    Log& log = result_.log;
    if (grid_.next_step() == n_) {
      if (active_) close_slip_event(t);
      result_.wheel_samples.push_back({t, truth_, left_.count(), right_.count(), left_.rim(), right_.rim(),
                                       left_.ground, right_.ground, left_.slip, right_.slip});
      if (sc_.encoders.timing.enabled && !replay_) {
        log.encoders.push_back({t + sc_.encoders.timing.latency, left_.count(), right_.count()});
      }
      grid_.advance();
      interval_pending_ = true;
    }
    if (!replay_ && odometry_clock_.next_step() == n_) {
      const double span = t - odo_last_t_;
      const double tv = span > 0.0 ? odo_distance_ / span : 0.0;
      const double rv = span > 0.0 ? odo_rotation_ / span : 0.0;
      log.odometry.push_back({t + sc_.odometry.timing.latency, belief_, tv, rv});
      odo_distance_ = odo_rotation_ = 0.0;
      odo_last_t_ = t;
      odometry_clock_.advance();
    }
    if (compass_clock_.next_step() == n_) {
      const CompassMeasurement m = compass_.measure(truth_);
      log.compass.push_back({t + sc_.compass.timing.latency, m.heading});
      result_.compass_truth.push_back({t, truth_.theta, m.disturbance});
      compass_clock_.advance();
    }
    if (laser_clock_.next_step() == n_) {
      LaserReading r;
      r.scan = laser_->measure(truth_, t + sc_.laser.timing.latency);
      r.pose = belief_;
      r.odom_pose = belief_;
      log.laser.push_back(std::move(r));
      laser_clock_.advance();
    }
    if (truth_clock_.next_step() == n_) {
      Pose2 reference = truth_;
      if (sc_.truth.noise_xy > 0.0 || sc_.truth.noise_theta > 0.0) {
        reference = Pose2(truth_.x + truth_noise_.normal(0.0, sc_.truth.noise_xy),
                          truth_.y + truth_noise_.normal(0.0, sc_.truth.noise_xy),
                          truth_.theta + truth_noise_.normal(0.0, sc_.truth.noise_theta));
      }
      log.truth.push_back({t, reference, belief_});
      truth_clock_.advance();
    }
    if (trajectory_clock_.next_step() == n_) {
      result_.trajectory.push_back({t, truth_});
      trajectory_clock_.advance();
    }
  }

  const Scenario& sc_;
  double dt_;
  RobotParams robot_;
  NominalModel nominal_;
  std::vector<Instruction> program_;
  FloorNoise floor_;
  SlipModel slip_;
  CompassModel compass_;
  MotionNoise motion_noise_;
  Rng truth_noise_;
  Rng stall_;
  double stall_until_ = -1.0;  // the current stall episode's end [s]
  bool replay_;
  DriveLag lag_;
  SensorClock grid_, odometry_clock_, compass_clock_, laser_clock_, truth_clock_, trajectory_clock_;
  std::optional<LaserModel> laser_;
  SimulationResult result_;

  std::int64_t n_ = 0;  // physics step index; time = n·dt
  Pose2 truth_;         // true pose
  Pose2 belief_;        // the robot's odometry pose (nominal model)
  Wheel left_, right_;
  std::int64_t fw_left_ = 0, fw_right_ = 0;  // counts the firmware has integrated
  double odo_distance_ = 0.0, odo_rotation_ = 0.0, odo_last_t_ = 0.0;

  std::size_t pc_ = 0;
  bool has_leg_ = false;
  Leg leg_;
  std::int64_t leg_i_ = 0;
  double leg_q0_left_ = 0.0, leg_q0_right_ = 0.0;
  Pose2 run_belief_start_;

  bool interval_pending_ = false;
  std::optional<ActiveSlip> active_;
  SlipEvent event_;
};

}  // namespace

SimulationResult simulate(const Scenario& scenario, std::uint64_t seed) {
  validate(scenario);
  return Simulation(scenario, seed).run();
}

}  // namespace locbench::sim
