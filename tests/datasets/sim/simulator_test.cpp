// The simulator as a whole: exact paths for the ideal robot, what goes into the log,
// determinism, the nominal/true split.
#include "datasets/sim/simulator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "datasets/sim/scenario_json.h"
#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

using testing::dead_reckon;
using testing::quiet_straight;

TEST(IdealSimulation, StraightTenMetresEndsExactlyAtTenZeroZero) {
  const auto r = simulate(quiet_straight(10.0), 1);
  const Pose2 end = r.log.truth.back().pose;
  EXPECT_NEAR(end.x, 10.0, 1e-9);
  EXPECT_NEAR(end.y, 0.0, 1e-9);
  EXPECT_NEAR(end.theta, 0.0, 1e-9);
  EXPECT_EQ(r.log.encoders.back().left, 100000);  // 10 m at exactly 0.1 mm per tick
  EXPECT_EQ(r.log.encoders.back().right, 100000);
  EXPECT_NEAR(r.duration, 40.5, 1e-9);  // 40 s driving + 0.5 s pause
}

TEST(IdealSimulation, SquareReturnsExactlyToTheStart) {
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kUmbmark;
  s.motion.side = 1.6;
  s.motion.runs = 1;
  s.start = Pose2(0.5, -0.25, 0.3);
  const auto r = simulate(s, 1);
  ASSERT_EQ(r.umbmark_runs.size(), 2u);
  for (const auto& run : r.umbmark_runs) {
    EXPECT_NEAR(run.true_end.x, 0.5, 1e-9);
    EXPECT_NEAR(run.true_end.y, -0.25, 1e-9);
    EXPECT_NEAR(angle_diff(run.true_end.theta, 0.3), 0.0, 1e-9);
    EXPECT_NEAR(run.error.norm(), 0.0, 1e-9);
  }
  // Half-way through the clockwise run (after two legs) the robot is at the opposite corner.
  const Pose2 corner = Pose2(0.5, -0.25, 0.3) * Pose2(1.6, -1.6, 0.0);
  bool passed = false;
  for (const auto& p : r.trajectory) {
    passed |= translation_distance(p.pose, corner) < 1e-9;
  }
  EXPECT_TRUE(passed);
}

TEST(IdealSimulation, DeadReckonedEncoderTicksReproduceTheTruePathExactly) {
  // Whole-tick legs and right-angle turns; a pause longer than the encoder period after every
  // leg means no sample mixes a straight and a turn, so eq. 1.3 is exact per sample.
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kUmbmark;
  s.motion.side = 1.6;
  s.motion.runs = 1;
  const auto r = simulate(s, 1);
  const auto cw_end = r.umbmark_runs[0].t_end;
  const auto dr = dead_reckon(r.log, s.start);
  ASSERT_EQ(dr.size(), r.log.truth.size());  // both at 10 Hz from t = 0
  for (std::size_t i = 0; i < dr.size() && r.log.truth[i].t <= cw_end; ++i) {
    ASSERT_DOUBLE_EQ(r.log.encoders[i].t, r.log.truth[i].t);
    EXPECT_NEAR(dr[i].x, r.log.truth[i].pose.x, 1e-9) << r.log.truth[i].t;
    EXPECT_NEAR(dr[i].y, r.log.truth[i].pose.y, 1e-9);
    EXPECT_NEAR(angle_diff(dr[i].theta, r.log.truth[i].pose.theta), 0.0, 1e-9);
  }
}

TEST(IdealSimulation, DeadReckoningAnyPathStaysWithinTheQuantizationBound) {
  // Waypoints at arbitrary distances and angles: the counts lag the wheels by less than one
  // tick C = 0.1 mm, i.e. position within ~C and heading within 2C/B.
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kWaypoints;
  s.motion.waypoints = {{1.2345, 0.6789}, {-0.4321, 2.0}, {0.0, 0.0}};
  s.encoders.timing.rate = 7.0;  // not aligned with the truth records
  s.truth.rate = 7.0;
  const auto r = simulate(s, 1);
  const auto dr = dead_reckon(r.log, s.start);
  const double c = r.log.nominal_model()->meters_per_tick_left;
  const double B = r.log.nominal_model()->wheelbase;
  ASSERT_EQ(dr.size(), r.log.truth.size());
  for (std::size_t i = 0; i < dr.size(); ++i) {
    EXPECT_LT(translation_distance(dr[i], r.log.truth[i].pose), 2.0 * c);
    EXPECT_LT(std::abs(angle_diff(dr[i].theta, r.log.truth[i].pose.theta)), 2.0 * c / B);
  }
  // At rest every wheel sits exactly on a tick: the final poses agree exactly.
  EXPECT_LT(translation_distance(dr.back(), r.log.truth.back().pose), 1e-9);
  // ...and the robot's own odometry (ODOM, TRUEPOS odom pose) agrees with the truth too.
  EXPECT_LT(translation_distance(r.log.truth.back().odom_pose, r.log.truth.back().pose), 1e-9);
}

TEST(Simulation, WrongWheelsSendTheTrueRobotAwayFromWhatItsOdometryBelieves) {
  Scenario s = quiet_straight(10.0);
  s.robot.actual.diameter_right *= 1.01;  // E_d = 1.01: the right wheel travels 1% further
  const auto r = simulate(s, 1);
  const auto& end = r.log.truth.back();
  EXPECT_NEAR(end.odom_pose.y, 0.0, 1e-9);  // the robot believes it drove straight
  EXPECT_NEAR(end.odom_pose.x, 10.0, 1e-9);
  // It really curved left: Δθ = (U_R − U_L)/B = 0.1 m / 0.382 m.
  EXPECT_NEAR(end.pose.theta, 0.1 / s.robot.actual.wheelbase, 1e-9);
  EXPECT_GT(end.pose.y, 1.0);
}

TEST(Simulation, LogLooksLikeARealRobotLog) {
  const auto r = simulate(preset("corridor"), 42);
  const Log& log = r.log;
  EXPECT_EQ(log.name, "sim/corridor");
  EXPECT_EQ(log.source, "simulated");
  ASSERT_TRUE(log.nominal_model().has_value());
  EXPECT_DOUBLE_EQ(log.nominal_model()->meters_per_tick_left,
                   preset("corridor").robot.params().nominal_model().meters_per_tick_left);
  EXPECT_EQ(log.params.at("sim_scenario"), "corridor");
  EXPECT_EQ(log.params.at("sim_seed"), "42");
  EXPECT_EQ(log.params.at("robot_encoder_counts_per_rev"), "22");
  EXPECT_DOUBLE_EQ(std::stod(log.params.at("compass_resolution")), deg(2.0));
  EXPECT_TRUE(log.laser.empty());     // the Trilobot has no laser
  EXPECT_TRUE(log.odometry.empty());  // ...and reports ticks, not velocities
  EXPECT_GT(log.encoders.size(), 150u);
  EXPECT_GT(log.compass.size(), 150u);
  for (std::size_t i = 1; i < log.encoders.size(); ++i) {
    EXPECT_GT(log.encoders[i].t, log.encoders[i - 1].t);
  }
  // The true robot parameters are in the result, not in the log.
  EXPECT_NE(r.robot.E_o(), 1.0);
  EXPECT_EQ(log.params.count("robot_actual_wheelbase"), 0u);
}

TEST(Simulation, LaserParamsUseTheCarmenNamesAndParamValuesAreSingleWords) {
  Scenario s = preset("room_laser");
  s.name = "my room run";
  s.laser.mount = Pose2(0.16, 0.0, 0.0);
  const auto r = simulate(s, 1);
  EXPECT_EQ(r.log.name, "sim/my room run");
  EXPECT_EQ(r.log.params.at("sim_scenario"), "my_room_run");
  EXPECT_EQ(r.log.params.at("sim_world"), "room");
  EXPECT_EQ(r.log.params.at("laser_front_laser_max_range"), "8");
  EXPECT_EQ(r.log.params.at("robot_frontlaser_offset"), "0.16");
  EXPECT_EQ(r.log.laser.front().scan.sensor_pose.x, 0.16);
  EXPECT_EQ(r.log.laser.front().scan.max_range, 8.0);
}

TEST(Simulation, OdometryRecordsCarryTheDeadReckonedPoseAndVelocities) {
  const auto r = simulate(preset("corridor_laser"), 1);
  ASSERT_GT(r.log.odometry.size(), 400u);
  const auto& mid = r.log.odometry[200];  // 20 s: cruising at 0.2 m/s
  EXPECT_NEAR(mid.tv, 0.2, 0.001);
  EXPECT_NEAR(mid.rv, 0.0, 1e-3);
  EXPECT_NEAR(mid.pose.x, 1.0 + 0.2 * 20.0, 0.01);
  EXPECT_EQ(r.log.odometry.back().tv, 0.0);  // stopped at the end
}

bool identical(const Log& a, const Log& b) {
  if (a.params != b.params || a.encoders.size() != b.encoders.size() || a.compass.size() != b.compass.size() ||
      a.laser.size() != b.laser.size() || a.truth.size() != b.truth.size() || a.odometry.size() != b.odometry.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.encoders.size(); ++i) {
    if (a.encoders[i].t != b.encoders[i].t || a.encoders[i].left != b.encoders[i].left ||
        a.encoders[i].right != b.encoders[i].right) {
      return false;
    }
  }
  for (std::size_t i = 0; i < a.compass.size(); ++i) {
    if (a.compass[i].t != b.compass[i].t || a.compass[i].heading != b.compass[i].heading) return false;
  }
  for (std::size_t i = 0; i < a.laser.size(); ++i) {
    if (a.laser[i].scan.ranges != b.laser[i].scan.ranges) return false;
  }
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    if (a.truth[i].pose.x != b.truth[i].pose.x || a.truth[i].pose.y != b.truth[i].pose.y ||
        a.truth[i].pose.theta != b.truth[i].pose.theta) {
      return false;
    }
  }
  for (std::size_t i = 0; i < a.odometry.size(); ++i) {
    if (a.odometry[i].pose.x != b.odometry[i].pose.x || a.odometry[i].tv != b.odometry[i].tv) return false;
  }
  return true;
}

TEST(Determinism, SameSeedGivesIdenticalLogs) {
  for (const char* name : {"corridor", "room_laser"}) {
    const auto a = simulate(preset(name), 123);
    const auto b = simulate(preset(name), 123);
    EXPECT_TRUE(identical(a.log, b.log)) << name;
    EXPECT_EQ(a.slips.size(), b.slips.size());
  }
}

TEST(Determinism, DifferentSeedsGiveDifferentNoise) {
  for (const char* name : {"corridor", "room_laser"}) {
    const auto a = simulate(preset(name), 1);
    const auto b = simulate(preset(name), 2);
    EXPECT_FALSE(identical(a.log, b.log)) << name;
    EXPECT_NE(a.log.truth.back().pose.y, b.log.truth.back().pose.y) << name;
  }
}

TEST(Determinism, TurningOnOneSensorLeavesTheOthersNoiseAlone) {
  Scenario s = preset("corridor");
  const auto a = simulate(s, 9);
  s.odometry.timing.enabled = true;
  s.laser.timing.enabled = true;
  s.laser.noise = 0.01;
  const auto b = simulate(s, 9);
  ASSERT_EQ(a.log.compass.size(), b.log.compass.size());
  for (std::size_t i = 0; i < a.log.compass.size(); ++i) {
    EXPECT_EQ(a.log.compass[i].heading, b.log.compass[i].heading);
  }
  EXPECT_EQ(a.log.truth.back().pose.x, b.log.truth.back().pose.x);
}

TEST(Simulation, RejectsAnInvalidScenario) {
  Scenario s;
  s.drive.speed = 0.0;
  EXPECT_THROW(simulate(s, 1), UsageError);
}

}  // namespace
}  // namespace locbench::sim
