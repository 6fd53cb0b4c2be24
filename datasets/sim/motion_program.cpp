#include "datasets/sim/motion_program.h"

#include <algorithm>
#include <cmath>

#include "core/angle.h"

namespace locbench::sim {
namespace {

Instruction make(Instruction::Kind kind, double value = 0.0) {
  Instruction i;
  i.kind = kind;
  i.value = value;
  return i;
}

void add_leg(std::vector<Instruction>& p, Instruction leg, double pause) {
  p.push_back(leg);
  p.push_back(make(Instruction::Kind::kPause, pause));
}

std::int64_t count(double travel, double meters_per_tick) { return std::llround(travel / meters_per_tick); }

}  // namespace

std::vector<Instruction> build_program(const MotionConfig& motion, const DriveConfig& drive, const Pose2& start) {
  using K = Instruction::Kind;
  std::vector<Instruction> p;
  switch (motion.kind) {
    case MotionKind::kStraight: add_leg(p, make(K::kStraight, motion.distance), drive.pause); break;
    case MotionKind::kUmbmark: {
      bool first = true;
      for (Direction dir : {Direction::kClockwise, Direction::kCounterClockwise}) {
        const double turn = dir == Direction::kClockwise ? -kPi / 2.0 : kPi / 2.0;
        for (int r = 0; r < motion.runs; ++r) {
          if (!first) {
            Instruction reset = make(K::kReset);
            reset.pose = start;
            p.push_back(reset);
          }
          first = false;
          Instruction begin = make(K::kRunBegin);
          begin.direction = dir;
          begin.run = r;
          p.push_back(begin);
          for (int side = 0; side < 4; ++side) {
            add_leg(p, make(K::kStraight, motion.side), drive.pause);
            add_leg(p, make(K::kTurn, turn), drive.pause);
          }
          p.push_back(make(K::kRunEnd));
        }
      }
      break;
    }
    case MotionKind::kWaypoints:
      for (const auto& w : motion.waypoints) {
        Instruction turn = make(K::kTurnToward);
        turn.target = w;
        add_leg(p, turn, drive.pause);
        Instruction go = make(K::kDriveTo);
        go.target = w;
        add_leg(p, go, drive.pause);
      }
      break;
    case MotionKind::kReplay: break;  // no legs: the simulator follows motion.commands (replay_wheel_speeds)
  }
  return p;
}

Instruction resolve(const Instruction& in, const Pose2& belief) {
  using K = Instruction::Kind;
  const Eigen::Vector2d d = in.target - belief.translation();
  if (in.kind == K::kTurnToward) {
    const double angle = d.norm() > 0.0 ? angle_diff(std::atan2(d.y(), d.x()), belief.theta) : 0.0;
    return make(K::kTurn, angle);
  }
  if (in.kind == K::kDriveTo) return make(K::kStraight, d.norm());
  return in;
}

WheelTicks straight_ticks(double distance, const NominalModel& m, bool equal_wheel_ticks) {
  if (equal_wheel_ticks) {
    const std::int64_t n = count(distance, 0.5 * (m.meters_per_tick_left + m.meters_per_tick_right));
    return {n, n};
  }
  return {count(distance, m.meters_per_tick_left), count(distance, m.meters_per_tick_right)};
}

WheelTicks turn_ticks(double angle, const NominalModel& m, bool equal_wheel_ticks) {
  const double arc = angle * m.wheelbase / 2.0;  // right wheel +arc, left wheel −arc (eq. 1.2)
  if (equal_wheel_ticks) {
    const std::int64_t n = count(arc, 0.5 * (m.meters_per_tick_left + m.meters_per_tick_right));
    return {-n, n};
  }
  return {-count(arc, m.meters_per_tick_left), count(arc, m.meters_per_tick_right)};
}

Leg plan_leg(const Instruction& in, const NominalModel& m, const DriveConfig& drive, double step) {
  using K = Instruction::Kind;
  Leg leg;
  double duration = 0.0;
  if (in.kind == K::kPause) {
    leg.steps = std::max<std::int64_t>(0, std::llround(in.value / step));
    return leg;
  }
  if (in.kind == K::kStraight) {
    leg.phase = MotionPhase::kStraight;
    leg.ticks = straight_ticks(in.value, m, drive.equal_wheel_ticks);
  } else if (in.kind == K::kTurn) {
    leg.phase = MotionPhase::kTurn;
    leg.ticks = turn_ticks(in.value, m, drive.equal_wheel_ticks);
  } else {
    return leg;  // not a leg
  }
  const double travel_left = std::abs(static_cast<double>(leg.ticks.left)) * m.meters_per_tick_left;
  const double travel_right = std::abs(static_cast<double>(leg.ticks.right)) * m.meters_per_tick_right;
  if (leg.ticks.left == 0 && leg.ticks.right == 0) return Leg{};
  if (leg.phase == MotionPhase::kStraight) {
    duration = std::max(travel_left, travel_right) / drive.speed;
  } else {
    duration = (travel_left + travel_right) / m.wheelbase / drive.turn_rate;
  }
  leg.steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(duration / step - 1e-6)));
  leg.wheel_speed = 0.5 * (travel_left + travel_right) / (static_cast<double>(leg.steps) * step);
  return leg;
}

WheelSpeeds replay_wheel_speeds(const BodyVelocity& b, double wheelbase) {
  return {b.v - 0.5 * b.omega * wheelbase, b.v + 0.5 * b.omega * wheelbase};
}

MotionPhase replay_phase(const WheelSpeeds& u) {
  if (u.left == 0.0 && u.right == 0.0) return MotionPhase::kIdle;
  return u.left * u.right < 0.0 ? MotionPhase::kTurn : MotionPhase::kStraight;
}

std::size_t replay_command_index(const std::vector<ReplayCommand>& commands, double t, std::size_t hint) {
  std::size_t i = std::min(hint, commands.size());
  while (i > 0 && commands[i - 1].t > t) --i;
  while (i < commands.size() && commands[i].t <= t) ++i;
  return i;
}

}  // namespace locbench::sim
