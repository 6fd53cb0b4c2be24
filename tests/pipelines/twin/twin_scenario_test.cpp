// The scenario writer: a diagnosis's kept causes become the extended twin's simulator settings;
// causes it cannot simulate are listed, never dropped.
#include "pipelines/twin/twin_scenario.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/sim/scenario_json.h"

namespace locbench::sim {
namespace {

diagnosis::Cause cause(std::string id, std::vector<std::pair<std::string, double>> params, bool detected = true,
                       std::string channel = "odometry") {
  diagnosis::Cause c;
  c.id = std::move(id);
  c.channel = std::move(channel);
  c.detected = detected;
  for (const auto& [name, value] : params) c.parameters.push_back({name, value, value, value});
  return c;
}

diagnosis::Diagnosis known_causes() {
  diagnosis::Diagnosis d;
  d.causes = {cause("velocity_scale", {{"scale", 0.95}}),
              cause("turn_rate_scale", {{"scale", 0.93}}),
              cause("turn_rate_bias", {{"bias_rad_s", -0.003}}),
              cause("sensor_time_offset", {{"offset_s", -0.21}}),
              cause("drive_response", {{"tau_s", 0.15}}),
              cause("odometry_noise_growth", {{"k2_m", 1e-4}}),
              cause("wheel_slip", {{"rate_per_m", 0.2}, {"mean_loss", 0.3}}),
              cause("heavy_tailed_noise", {{"dof", 4.0}}),
              cause("compass_bias", {{"bias_rad", 0.01}}, true, "compass"),
              cause("mystery_cause", {{"x", 1.0}}),
              cause("wheelbase_scale", {{"E_b", 1.2}}, false)};  // not kept: must not act
  d.causes.front().extra = nlohmann::json::object();
  d.causes[3].extra["sensor"] = "odometry";
  return d;
}

TEST(TwinScenario, KeptCausesBecomeTheirSimulatorSettings) {
  Scenario s;
  s.odometry.timing.enabled = true;
  const auto mapping = apply_causes(known_causes(), s);
  EXPECT_DOUBLE_EQ(s.drive.response.velocity_scale, 0.95);
  EXPECT_DOUBLE_EQ(s.drive.response.turn_rate_scale, 0.93);
  EXPECT_DOUBLE_EQ(s.drive.response.turn_rate_bias, -0.003);
  EXPECT_DOUBLE_EQ(s.drive.response.time_constant, 0.15);
  EXPECT_DOUBLE_EQ(s.odometry.timing.latency, -0.21);
  EXPECT_DOUBLE_EQ(s.floor.k_left, 0.01);  // √1e-4
  EXPECT_DOUBLE_EQ(s.floor.k_right, 0.01);
  EXPECT_EQ(s.slip.unit, SlipRateUnit::kPerMetre);
  EXPECT_DOUBLE_EQ(s.slip.straight.rate, 0.2);
  EXPECT_DOUBLE_EQ(0.5 * (s.slip.turn.magnitude_min + s.slip.turn.magnitude_max), 0.3);
  EXPECT_DOUBLE_EQ(s.motion_noise.dof, 4.0);
  EXPECT_DOUBLE_EQ(s.robot.actual.wheelbase, s.robot.nominal.wheelbase);  // wheelbase_scale was not kept
  ASSERT_EQ(mapping.size(), 10u);                                         // every kept cause, none of the others
  std::vector<std::string> not_simulated;
  for (const auto& m : mapping) {
    if (!m.simulated) not_simulated.push_back(m.id);
  }
  EXPECT_EQ(not_simulated, (std::vector<std::string>{"compass_bias", "mystery_cause"}));
}

TEST(TwinScenario, WheelGeometryFactorsSetTheTrueWheels) {
  diagnosis::Diagnosis d;
  d.causes = {cause("wheel_diameter_ratio", {{"E_d", 1.002}}), cause("wheelbase_scale", {{"E_b", 1.01}}),
              cause("mean_diameter_scale", {{"E_o", 0.99}})};
  Scenario s;
  apply_causes(d, s);
  const double dn = s.robot.nominal.diameter_left;
  EXPECT_NEAR(s.robot.actual.diameter_right / s.robot.actual.diameter_left, 1.002, 1e-12);  // E_d = D_R/D_L
  EXPECT_NEAR(0.5 * (s.robot.actual.diameter_left + s.robot.actual.diameter_right), 0.99 * dn, 1e-12);
  EXPECT_NEAR(s.robot.actual.wheelbase, 1.01 * s.robot.nominal.wheelbase, 1e-12);
}

TEST(TwinScenario, SpeedDependentScaleComposesWithAVelocityScale) {
  diagnosis::Diagnosis d;
  d.causes = {cause("speed_dependent_scale", {{"scale_at_0", 0.98}, {"slope_s_per_m", -0.1}}),
              cause("velocity_scale", {{"scale", 0.9}})};
  Scenario s;
  apply_causes(d, s);
  EXPECT_NEAR(s.drive.response.velocity_scale, 0.882, 1e-12);
  EXPECT_NEAR(s.drive.response.speed_slope, -0.09, 1e-12);
}

TEST(TwinScenario, DriveStallsBecomeTheDrivesStallRateAndDuration) {
  diagnosis::Diagnosis d;
  d.causes = {cause("drive_stall", {{"rate_per_s", 0.14}, {"duration_s", 0.37}})};
  Scenario s;
  const auto mapping = apply_causes(d, s);
  ASSERT_EQ(mapping.size(), 1u);
  EXPECT_TRUE(mapping[0].simulated) << mapping[0].how;
  EXPECT_EQ(s.drive.response.stall_rate, 0.14);
  EXPECT_EQ(s.drive.response.stall_duration, 0.37);
}

TEST(TwinScenario, TheWrittenScenarioReplaysTheLogAndListsWhatItCannotSimulate) {
  GeneratorOptions o;
  o.velocity_odometry = true;
  o.waypoints = 6;
  const Log log = generate_log({}, 5, o).log;
  const Twin twin = build_twin(log, known_causes());
  EXPECT_EQ(twin.not_simulated, (std::vector<std::string>{"compass_bias", "mystery_cause"}));
  const auto j = to_json(twin.extended);
  EXPECT_EQ(j["motion"]["kind"], "replay");
  EXPECT_EQ(j["motion"]["commands"].size(), log.odometry.size());
  EXPECT_EQ(j["drive"]["response"]["velocity_scale"], 0.95);
  EXPECT_EQ(j["odometry"]["latency"], -0.21);
  const auto notes = j["notes"].get<std::vector<std::string>>();
  const auto has = [&](const std::string& text) {
    return std::any_of(notes.begin(), notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has("mystery_cause: not simulated")) << j["notes"].dump(1);
  EXPECT_TRUE(has("compass_bias: not simulated")) << j["notes"].dump(1);
  // The nominal twin has none of the causes, and says which ones the extended twin lacks.
  EXPECT_EQ(twin.nominal.drive.response.velocity_scale, 1.0);
  EXPECT_EQ(twin.nominal.odometry.timing.latency, 0.0);
  // The scenario reads back as written: `locbench simulate twin.json` sees this very scenario.
  EXPECT_EQ(to_json(scenario_from_json(j)), j);
  // Logged time = twin time + origin; the first command starts after 1 s of standing.
  EXPECT_NEAR(twin.extended.motion.commands.front().t + twin.time_origin, log.odometry.front().t, 1e-9);
}

TEST(TwinScenario, ReferenceNoiseIsReadFromTheSecondDifferencesOfTheTruth) {
  GeneratorOptions o;
  o.velocity_odometry = true;
  o.waypoints = 4;
  o.reference_noise_xy = 2e-3;
  o.reference_noise_theta = 1e-3;
  const Log log = generate_log({}, 8, o).log;
  const auto [xy, th] = reference_noise(log.truth);
  EXPECT_NEAR(xy, 2e-3, 2e-4);
  EXPECT_NEAR(th, 1e-3, 1e-4);
}

}  // namespace
}  // namespace locbench::sim
