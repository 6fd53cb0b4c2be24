// motion.kind = "replay": a logged command sequence drives the simulated robot; the drive's
// response (drive_response.h), the odometry latency and the motion noise (motion_noise.h) act
// on the truth while the replayed odometry is logged as commanded.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/statistics.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"

namespace locbench::sim {
namespace {

// Standing until t = 1 s, then the given commands; ODOM logged, truth at 100 Hz, no noise.
Scenario replay(std::vector<ReplayCommand> commands) {
  Scenario s;
  s.motion.kind = MotionKind::kReplay;
  s.motion.commands = std::move(commands);
  s.odometry.timing.enabled = true;
  s.encoders.timing.enabled = false;
  s.truth.rate = 100.0;
  return s;
}

Pose2 truth_at(const SimulationResult& r, double t) {
  for (const auto& p : r.log.truth) {
    if (std::abs(p.t - t) < 1e-9) return p.pose;
  }
  ADD_FAILURE() << "no TRUEPOS at " << t;
  return {};
}

TEST(SimulatorReplay, ConstantCommandDrivesItsDistanceAndIsLoggedAsCommanded) {
  const auto r = simulate(replay({{1.0, 0.2, 0.0}, {11.0, 0.0, 0.0}}), 1);
  EXPECT_NEAR(truth_at(r, 1.0).x, 0.0, 1e-9);
  EXPECT_NEAR(truth_at(r, 11.0).x, 2.0, 1e-6);  // 0.2 m/s × 10 s
  EXPECT_NEAR(truth_at(r, 11.0).y, 0.0, 1e-9);
  ASSERT_EQ(r.log.odometry.size(), 2u);
  EXPECT_DOUBLE_EQ(r.log.odometry[0].t, 1.0);
  EXPECT_DOUBLE_EQ(r.log.odometry[0].tv, 0.2);
  EXPECT_DOUBLE_EQ(r.log.odometry[1].t, 11.0);
  EXPECT_NEAR(r.log.odometry[1].pose.x, 2.0, 1e-12);
  EXPECT_NEAR(r.duration, 11.0, 1e-9);
}

TEST(SimulatorReplay, DriveResponseScalesLagsAndBiasesTheTrueMotion) {
  Scenario s = replay({{1.0, 0.2, 0.0}, {11.0, 0.0, 0.0}});
  s.drive.response.velocity_scale = 0.9;
  EXPECT_NEAR(truth_at(simulate(s, 1), 11.0).x, 1.8, 1e-6);

  s.drive.response = {};
  s.drive.response.time_constant = 0.5;
  // x(10 s) = v·(T − τ(1 − e^{−T/τ})) = 0.2·(10 − 0.5) = 1.9 m; the lag carries on after the stop.
  EXPECT_NEAR(truth_at(simulate(s, 1), 11.0).x, 1.9, 3e-4);

  s.drive.response = {};
  s.drive.response.speed_slope = 0.5;  // scale 1 + 0.5 s/m × 0.2 m/s = 1.1
  EXPECT_NEAR(truth_at(simulate(s, 1), 11.0).x, 2.2, 1e-6);

  Scenario turn = replay({{1.0, 0.0, 0.1}, {11.0, 0.0, 0.0}});
  turn.drive.response.turn_rate_scale = 1.1;
  turn.drive.response.turn_rate_bias = 0.01;
  // 1.1 × 0.1 rad/s × 10 s + 0.01 rad/s × 11 s (the bias acts from the start, standing or not).
  EXPECT_NEAR(truth_at(simulate(turn, 1), 11.0).theta, 1.1 + 0.11, 1e-6);
}

TEST(SimulatorReplay, StallsStopTheRobotForTheirDurationAtTheirRate) {
  // 0.2 m/s for 1000 s; stalls at 0.1/s of 0.5 s: the robot stands still for about 1 − e^{−0.05}
  // ≈ 4.9% of the time (a new stall starts only after the last one ends), so it covers ≈ 190 m.
  Scenario s = replay({{1.0, 0.2, 0.0}, {1001.0, 0.0, 0.0}});
  s.truth.rate = 10.0;
  s.drive.response.stall_rate = 0.1;
  s.drive.response.stall_duration = 0.5;
  const double x = truth_at(simulate(s, 3), 1001.0).x;
  const double stopped = 1.0 - x / 200.0;
  EXPECT_NEAR(stopped, 0.05 / 1.05, 0.015);  // ±3σ of ~95 episodes
  EXPECT_EQ(truth_at(simulate(s, 3), 1001.0).x, x) << "same seed, same stalls";
  EXPECT_NE(truth_at(simulate(s, 4), 501.0).x, truth_at(simulate(s, 3), 501.0).x) << "another seed, other stalls";
}

TEST(SimulatorReplay, OdometryLatencyMovesTheTruthEarlierThanTheLoggedStamps) {
  Scenario s = replay({{1.0, 0.2, 0.0}, {11.0, 0.0, 0.0}});
  s.odometry.timing.latency = 0.3;  // logged = true + 0.3 s: the command stamped 1.0 runs from 0.7
  const auto r = simulate(s, 1);
  EXPECT_NEAR(truth_at(r, 0.7).x, 0.0, 1e-9);
  EXPECT_NEAR(truth_at(r, 1.0).x, 0.06, 1e-6);
  EXPECT_NEAR(truth_at(r, 10.7).x, 2.0, 1e-6);
  EXPECT_DOUBLE_EQ(r.log.odometry[0].t, 1.0);  // the stamps are the logged ones

  s.odometry.timing.latency = 1.5;  // the first command would run before the simulation starts
  EXPECT_THROW(simulate(s, 1), UsageError);
}

TEST(SimulatorReplay, EncoderReplayLogsTheCountsTheCommandsMake) {
  Scenario s = replay({{1.0, 0.2, 0.0}, {6.0, 0.0, 0.1}, {11.0, 0.0, 0.0}});
  s.odometry.timing.enabled = false;
  s.encoders.timing.enabled = true;
  const auto r = simulate(s, 1);
  ASSERT_EQ(r.log.encoders.size(), 3u);
  // 1 m at 0.1 mm per tick; then a 0.5 rad turn: ±0.5·B/2 = ±0.5·(1.2/π)/2 m = ±954.93 ticks.
  EXPECT_EQ(r.log.encoders[1].left, 10000);
  EXPECT_EQ(r.log.encoders[1].right, 10000);
  EXPECT_NEAR(static_cast<double>(r.log.encoders[2].right - r.log.encoders[1].right), 954.93, 1.0);
  EXPECT_NEAR(static_cast<double>(r.log.encoders[2].left - r.log.encoders[1].left), -954.93, 1.0);
}

// The displacements over consecutive `window`-second stretches of the truth (x, standing still).
std::vector<double> window_steps(const SimulationResult& r, double window) {
  std::vector<double> out;
  double last_t = 0.0, last_x = 0.0;
  for (const auto& p : r.log.truth) {
    if (p.t - last_t >= window - 1e-9) {
      out.push_back(p.pose.x - last_x);
      last_t = p.t;
      last_x = p.pose.x;
    }
  }
  return out;
}

TEST(SimulatorReplay, MotionNoiseHasItsStandardDeviationPerWindowAndHeavyTailsWhenAsked) {
  Scenario s = replay({{1.0, 0.0, 0.0}, {1001.0, 0.0, 0.0}});
  s.truth.rate = 10.0;
  s.motion_noise.window = 1.0;
  s.motion_noise.sigma_along = 0.01;
  const auto gaussian = window_steps(simulate(s, 7), 1.0);
  ASSERT_GE(gaussian.size(), 990u);
  EXPECT_NEAR(sample_stddev(gaussian), 0.01, 0.001);
  const double k_gauss = central_moment(gaussian, 4) / std::pow(central_moment(gaussian, 2), 2) - 3.0;
  EXPECT_LT(std::abs(k_gauss), 0.6);

  s.motion_noise.dof = 4.0;  // Student-t₄: excess kurtosis infinite in theory, large in samples
  const auto heavy = window_steps(simulate(s, 7), 1.0);
  const double k_heavy = central_moment(heavy, 4) / std::pow(central_moment(heavy, 2), 2) - 3.0;
  EXPECT_GT(k_heavy, 1.5);
  // Student-t scale σ: the median |step| is σ·t₄⁻¹(0.75) = 0.741σ.
  std::vector<double> abs_heavy;
  for (double v : heavy) abs_heavy.push_back(std::abs(v));
  EXPECT_NEAR(quantile(abs_heavy, 0.5), 0.741 * 0.01, 0.001);
}

TEST(SimulatorReplay, TruthNoiseIsAddedToTheReferenceOnly) {
  Scenario s = replay({{1.0, 0.0, 0.0}, {101.0, 0.0, 0.0}});
  s.truth.noise_xy = 0.002;
  s.truth.noise_theta = 0.001;
  const auto r = simulate(s, 3);
  std::vector<double> x, th;
  for (const auto& p : r.log.truth) {
    x.push_back(p.pose.x);
    th.push_back(p.pose.theta);
  }
  EXPECT_NEAR(sample_stddev(x), 0.002, 0.0002);
  EXPECT_NEAR(sample_stddev(th), 0.001, 0.0001);
  EXPECT_NEAR(r.trajectory.back().pose.x, 0.0, 1e-12);  // the robot itself stood still
}

TEST(SimulatorReplay, ScenarioJsonRoundTripsAndNamesBadCommands) {
  Scenario s = replay({{1.0, 0.2, 0.0}, {2.0, 0.1, -0.3}});
  s.drive.response.time_constant = 0.2;
  s.motion_noise.sigma_heading = 0.003;
  s.motion_noise.dof = 5.0;
  s.truth.noise_xy = 0.001;
  s.notes = {"wheel_slip: not simulated"};
  const auto j = to_json(s);
  EXPECT_EQ(j["motion"]["kind"], "replay");
  EXPECT_EQ(j["motion"]["commands"][1][2], -0.3);
  EXPECT_EQ(to_json(scenario_from_json(j)), j);

  auto bad = j;
  bad["motion"]["commands"][1][0] = 0.5;  // earlier than the command before it
  try {
    scenario_from_json(bad, "twin.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("motion.commands[1][0]"), std::string::npos) << e.what();
  }
  bad = j;
  bad["motion"]["commands"][0] = {1.0, 0.2};
  EXPECT_THROW(scenario_from_json(bad, "twin.json"), InputError);
  bad = j;
  bad["notes"] = {3};
  EXPECT_THROW(scenario_from_json(bad, "twin.json"), InputError);
}

}  // namespace
}  // namespace locbench::sim
