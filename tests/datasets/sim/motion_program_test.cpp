// Motion programs: legs and turns commanded in encoder counts from the nominal model.
#include "datasets/sim/motion_program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

const NominalModel kTrilobot{0.012638, 0.012699, 0.19793};

TEST(StraightTicks, RoundTheDistanceOverEachWheelsMetresPerTick) {
  const WheelTicks t = straight_ticks(10.0, kTrilobot, false);
  EXPECT_EQ(t.left, 791);   // 10 / 0.012638 = 791.26
  EXPECT_EQ(t.right, 787);  // 10 / 0.012699 = 787.46
  const WheelTicks back = straight_ticks(-10.0, kTrilobot, false);
  EXPECT_EQ(back.left, -791);
}

TEST(StraightTicks, EqualWheelTicksGiveBothWheelsTheMeanCount) {
  const WheelTicks t = straight_ticks(10.0, kTrilobot, true);
  EXPECT_EQ(t.left, 789);  // 10 / 0.0126685
  EXPECT_EQ(t.right, 789);
}

TEST(TurnTicks, TurnEachWheelByHalfTheWheelbaseTimesTheAngle) {
  // 90° with B = 0.19793 m: each wheel travels 0.15546 m → 12.3 / 12.24 ticks → 12.
  const WheelTicks ccw = turn_ticks(kPi / 2, kTrilobot, false);
  EXPECT_EQ(ccw.left, -12);
  EXPECT_EQ(ccw.right, 12);
  const WheelTicks cw = turn_ticks(-kPi / 2, kTrilobot, false);
  EXPECT_EQ(cw.left, 12);
  EXPECT_EQ(cw.right, -12);
  // The default robot: a quarter turn is exactly 3000 ticks per wheel.
  const NominalModel ideal = RobotConfig{}.params().nominal_model();
  EXPECT_EQ(turn_ticks(kPi / 2, ideal, false).right, 3000);
  EXPECT_EQ(straight_ticks(1.6, ideal, false).left, 16000);
}

TEST(PlanLeg, LastsTheCommandedDistanceOverTheSpeed) {
  DriveConfig d;
  d.speed = 0.25;
  const NominalModel ideal = RobotConfig{}.params().nominal_model();
  Instruction in;
  in.kind = Instruction::Kind::kStraight;
  in.value = 10.0;
  const Leg leg = plan_leg(in, ideal, d, 1e-3);
  EXPECT_EQ(leg.phase, MotionPhase::kStraight);
  EXPECT_EQ(leg.steps, 40000);
  EXPECT_NEAR(leg.wheel_speed, 0.25, 1e-12);
  in.kind = Instruction::Kind::kTurn;
  in.value = kPi / 2;
  EXPECT_EQ(plan_leg(in, ideal, d, 1e-3).steps, 3000);  // 90° at 30°/s
  in.kind = Instruction::Kind::kPause;
  in.value = 0.5;
  EXPECT_EQ(plan_leg(in, ideal, d, 1e-3).steps, 500);
}

TEST(BuildProgram, UmbmarkRunsTheSquareClockwiseThenCounterClockwise) {
  MotionConfig m;
  m.kind = MotionKind::kUmbmark;
  m.side = 1.6;
  m.runs = 2;
  const auto p = build_program(m, DriveConfig{}, Pose2(1.0, 2.0, 0.3));
  using K = Instruction::Kind;
  int begins = 0, resets = 0, turns_cw = 0, turns_ccw = 0, straights = 0;
  for (const auto& i : p) {
    begins += i.kind == K::kRunBegin;
    resets += i.kind == K::kReset;
    straights += i.kind == K::kStraight && i.value == 1.6;
    turns_cw += i.kind == K::kTurn && i.value == -kPi / 2;
    turns_ccw += i.kind == K::kTurn && i.value == kPi / 2;
  }
  EXPECT_EQ(begins, 4);
  EXPECT_EQ(resets, 3);  // before every run but the first
  EXPECT_EQ(straights, 16);
  EXPECT_EQ(turns_cw, 8);
  EXPECT_EQ(turns_ccw, 8);
  EXPECT_EQ(p[0].kind, K::kRunBegin);
  EXPECT_EQ(p[0].direction, Direction::kClockwise);
  EXPECT_EQ(p.back().kind, K::kRunEnd);
}

TEST(Resolve, TurnsTowardsAndDrivesToTheWaypointFromTheBelief) {
  Instruction turn;
  turn.kind = Instruction::Kind::kTurnToward;
  turn.target = {3.0, 2.0};
  const Instruction t = resolve(turn, Pose2(2.0, 1.0, deg(46.0)));
  EXPECT_EQ(t.kind, Instruction::Kind::kTurn);
  EXPECT_NEAR(t.value, deg(45.0) - deg(46.0), 1e-12);
  Instruction go = turn;
  go.kind = Instruction::Kind::kDriveTo;
  const Instruction g = resolve(go, Pose2(2.0, 1.0, deg(45.0)));
  EXPECT_EQ(g.kind, Instruction::Kind::kStraight);
  EXPECT_NEAR(g.value, std::sqrt(2.0), 1e-12);
}

TEST(WaypointsInSimulation, TheRobotBelievesItReachedEveryWaypoint) {
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kWaypoints;
  s.motion.waypoints = {{2.0, 0.0}, {2.0, 1.5}, {0.5, 1.5}};
  const auto r = simulate(s, 1);
  const Pose2 end = r.log.odometry.back().pose;
  // Within the 0.1 mm tick and the rounding of each turn (≤ 0.5 tick over B/2).
  EXPECT_NEAR(end.x, 0.5, 1e-3);
  EXPECT_NEAR(end.y, 1.5, 1e-3);
  EXPECT_NEAR(r.log.truth.back().pose.x, 0.5, 1e-3);
}

TEST(ReplayCommandIndex, CountsTheCommandsDueByTheTimeFromAnyHint) {
  const std::vector<ReplayCommand> commands{{1.0, 0.1, 0.0}, {2.0, 0.2, 0.0}, {2.5, 0.0, 0.1}, {4.0, 0.0, 0.0}};
  const std::vector<std::pair<double, std::size_t>> due{{0.5, 0}, {1.0, 1}, {1.9, 1}, {2.0, 2},
                                                        {3.0, 3}, {4.0, 4}, {9.0, 4}};
  for (const auto& [time, count] : due) {
    for (std::size_t hint = 0; hint <= commands.size() + 2; ++hint) {
      EXPECT_EQ(replay_command_index(commands, time, hint), count) << "time " << time << ", hint " << hint;
    }
  }
  EXPECT_EQ(replay_command_index({}, 1.0, 3), 0U);
}

}  // namespace
}  // namespace locbench::sim
