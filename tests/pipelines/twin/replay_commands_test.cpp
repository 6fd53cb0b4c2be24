// Replaying a log's own odometry: the commands it gives, and a simulated robot following them
// under the nominal model retracing the logged odometry path.
#include "pipelines/twin/replay_commands.h"

#include <gtest/gtest.h>

#include "core/angle.h"
#include "core/errors.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/sim/simulator.h"

namespace locbench::sim {
using io::interpolate_truth;
namespace {

TEST(ReplayCommands, VelocityOdometryGivesBackTheLoggedVelocities) {
  Log log;
  log.name = "mrclam-like";
  // Poses integrated by the midpoint rule from v = 0.2, ω = 0.5 held over 0.1 s, then v = −0.1.
  log.odometry.push_back({0.0, Pose2(0, 0, 0), 0.2, 0.5});
  const double th = 0.05;
  log.odometry.push_back({0.1, Pose2(0.02 * std::cos(0.025), 0.02 * std::sin(0.025), th), -0.1, 0.0});
  log.odometry.push_back(
      {0.3, Pose2(log.odometry[1].pose.x - 0.02 * std::cos(th), log.odometry[1].pose.y - 0.02 * std::sin(th), th), 0,
       0});
  const ReplaySource src = replay_commands(log, -1e9, 1e9);
  EXPECT_EQ(src.odometry, "ODOM");
  ASSERT_EQ(src.commands.size(), 3u);
  EXPECT_NEAR(src.commands[0].v, 0.2, 1e-12);
  EXPECT_NEAR(src.commands[0].omega, 0.5, 1e-12);
  EXPECT_NEAR(src.commands[1].v, -0.1, 1e-12);  // backwards: signed along the mid heading
  EXPECT_DOUBLE_EQ(src.commands[2].t, 0.3);
  EXPECT_DOUBLE_EQ(src.commands[2].v, 0.0);  // the last record: standing
  EXPECT_EQ(replay_commands(log, 0.05, 1e9).commands.size(), 2u);
  EXPECT_THROW(replay_commands(log, 0.2, 0.25), InputError);
}

TEST(ReplayCommands, EncoderCountsBecomeVelocitiesThroughTheNominalModel) {
  Log log;
  log.params[kParamMetersPerTickLeft] = "0.001";
  log.params[kParamMetersPerTickRight] = "0.001";
  log.params[kParamWheelbase] = "0.5";
  log.encoders = {{0.0, 0, 0}, {0.5, 100, 300}, {1.0, 100, 300}};
  const ReplaySource src = replay_commands(log, -1e9, 1e9);
  EXPECT_EQ(src.odometry, "ENCODER");
  EXPECT_NEAR(src.commands[0].v, 0.4, 1e-12);      // (0.1 + 0.3)/2 m over 0.5 s
  EXPECT_NEAR(src.commands[0].omega, 0.8, 1e-12);  // (0.3 − 0.1)/0.5 rad over 0.5 s
  log.params.erase(kParamWheelbase);
  EXPECT_THROW(replay_commands(log, -1e9, 1e9), InputError);
}

TEST(ReplayCommands, ReplayingASimulatedLogUnderTheNominalModelRetracesItsOdometryPath) {
  GeneratorOptions o;
  o.velocity_odometry = true;
  o.waypoints = 6;
  const Log log = generate_log({}, 11, o).log;
  ASSERT_GT(log.odometry.size(), 100u);
  Scenario s;
  s.motion.kind = MotionKind::kReplay;
  s.motion.commands = replay_commands(log, -1e9, 1e9).commands;
  s.start = log.odometry.front().pose;
  s.odometry.timing.enabled = true;
  s.encoders.timing.enabled = false;
  s.truth.rate = 1000.0;
  const Log twin = simulate(s, 1).log;
  ASSERT_EQ(twin.odometry.size(), log.odometry.size());
  double worst_xy = 0.0, worst_th = 0.0;
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    EXPECT_DOUBLE_EQ(twin.odometry[i].t, log.odometry[i].t);
    const auto truth = interpolate_truth(twin, log.odometry[i].t);
    ASSERT_TRUE(truth) << "t = " << log.odometry[i].t;
    const Pose2& p = log.odometry[i].pose;
    worst_xy = std::max(worst_xy, std::hypot(truth->x - p.x, truth->y - p.y));
    worst_th = std::max(worst_th, std::abs(angle_diff(truth->theta, p.theta)));
    worst_xy = std::max(worst_xy, std::hypot(twin.odometry[i].pose.x - p.x, twin.odometry[i].pose.y - p.y));
  }
  // Over the whole path (tens of metres): the truth the twin simulates is the logged odometry.
  EXPECT_LT(worst_xy, 2e-3) << "worst position difference [m]";
  EXPECT_LT(worst_th, 1e-3) << "worst heading difference [rad]";
}

}  // namespace
}  // namespace locbench::sim
