#pragma once
// Motion programs: what the robot is told to do, and how a command becomes encoder counts.
// Every straight leg and every on-the-spot turn is commanded in encoder counts computed from the
// nominal model; the servo then turns each wheel by exactly that many (true) ticks, so a robot
// whose true geometry differs from its nominal one really ends up elsewhere (UMBmark, §2.1).
// Waypoints are reached by "turn on the spot towards the waypoint, then drive straight to it",
// both computed from the robot's own odometry pose (its belief) when the leg starts.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/pose2.h"
#include "core/robot_params.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

enum class Direction { kClockwise, kCounterClockwise };

struct Instruction {
  enum class Kind {
    kStraight,    // value = distance [m]
    kTurn,        // value = angle [rad], counter-clockwise positive
    kPause,       // value = duration [s]
    kTurnToward,  // target: turn on the spot to face it (resolved from the belief)
    kDriveTo,     // target: drive straight by the distance to it (resolved from the belief)
    kReset,       // pose: the robot is put back there; its odometry restarts there too
    kRunBegin,    // direction, run: an UMBmark run starts
    kRunEnd,      // an UMBmark run ends (the robot has stopped)
  };
  Kind kind = Kind::kPause;
  double value = 0.0;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
  Pose2 pose;
  Direction direction = Direction::kClockwise;
  int run = 0;
};

// The instruction list for a scenario's motion: a straight leg; the UMBmark square (`runs` CW
// then `runs` CCW, each run: 4 × [side, pause, ∓90° turn, pause], the robot reset to the start
// before every run but the first); or the waypoint path. A pause follows every leg.
std::vector<Instruction> build_program(const MotionConfig& motion, const DriveConfig& drive, const Pose2& start);

// kTurnToward / kDriveTo → kTurn / kStraight computed from the robot's belief; others unchanged.
Instruction resolve(const Instruction& in, const Pose2& belief);

struct WheelTicks {
  std::int64_t left = 0;
  std::int64_t right = 0;
};
// Counts for a straight leg: round(d / c) per wheel (or the same rounded mean count for both).
WheelTicks straight_ticks(double distance, const NominalModel& m, bool equal_wheel_ticks);
// Counts for an on-the-spot turn by `angle`: each wheel travels ±angle·B/2 (eq. 1.2 inverted).
WheelTicks turn_ticks(double angle, const NominalModel& m, bool equal_wheel_ticks);

enum class MotionPhase { kIdle, kStraight, kTurn };

// One leg as the servo executes it: each wheel moves linearly in (true) tick units by `ticks`
// over `steps` physics steps.
struct Leg {
  MotionPhase phase = MotionPhase::kIdle;
  WheelTicks ticks;
  std::int64_t steps = 0;
  double wheel_speed = 0.0;  // nominal mean |wheel speed| [m/s], for per-metre slip rates
};
// kStraight, kTurn or kPause → a leg; steps == 0 means nothing to do.
Leg plan_leg(const Instruction& in, const NominalModel& m, const DriveConfig& drive, double step);

// Replayed motion (MotionKind::kReplay) has no legs: at every physics step the command in force
// (after the drive's response, drive_response.h) is turned into nominal wheel speeds, which the
// servo follows in (nominal) ticks, so the true geometry acts as it does on legs.
struct WheelSpeeds {
  double left = 0.0, right = 0.0;  // [m/s]
};
// u_L = v − ω·B/2, u_R = v + ω·B/2 (eq. 1.2 inverted).
WheelSpeeds replay_wheel_speeds(const BodyVelocity& b, double wheelbase);
// Idle when both wheels stand, a turn when they turn in opposite directions, else straight
// (which slip profile applies).
MotionPhase replay_phase(const WheelSpeeds& u);
// The number of commands with t ≤ time: the command in force is the one before that index
// (none when 0). The commands are in increasing time; the search steps from `hint`, the index
// of an earlier call (a simulation asks for times in increasing order).
std::size_t replay_command_index(const std::vector<ReplayCommand>& commands, double time, std::size_t hint = 0);

}  // namespace locbench::sim
