// Scenario JSON: full round trip, strict keys and types, presets as a base, validation.
#include "datasets/sim/scenario_json.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "datasets/sim/presets.h"
#include "tests/test_data.h"

namespace locbench::sim {
namespace {

using nlohmann::json;

// Expects InputError whose message contains every fragment.
template <typename F>
void expect_input_error(F f, std::initializer_list<const char*> fragments) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const char* frag : fragments) {
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what() << " / " << frag;
    }
  }
}

Scenario everything_set() {
  Scenario s = preset("room_laser");
  s.name = "custom";
  s.world.kind = WorldKind::kInline;
  s.world.segments = {{0.0, 0.0, 1.0, 0.5}, {1.0, 0.5, 2.0, 2.0}};
  s.drive.equal_wheel_ticks = true;
  s.slip.unit = SlipRateUnit::kPerMetre;
  s.compass.timing = {true, 4.0, -0.05, 0.01};
  s.compass.resolution = deg(2.0);
  DisturbanceZone circle;
  circle.shape = DisturbanceZone::Shape::kCircle;
  circle.center = {1.5, 2.5};
  circle.radius = 0.75;
  circle.bias = 0.1;
  DisturbanceZone rect;
  rect.min = {0.0, 1.0};
  rect.max = {2.0, 3.0};
  rect.bias = -0.2;
  s.compass.zones = {circle, rect};
  s.laser.mount = Pose2(0.16, 0.01, 0.02);
  s.physics.step = 0.5e-3;
  return s;
}

TEST(ScenarioJson, RoundTripsEveryField) {
  const Scenario s = everything_set();
  const json j = to_json(s);
  const Scenario back = scenario_from_json(j);
  EXPECT_EQ(to_json(back), j);
  EXPECT_EQ(back.world.segments.size(), 2u);
  EXPECT_EQ(back.compass.zones[0].shape, DisturbanceZone::Shape::kCircle);
  EXPECT_EQ(back.compass.zones[0].radius, 0.75);
  EXPECT_EQ(back.compass.zones[1].max.y(), 3.0);
  EXPECT_EQ(back.laser.mount.x, 0.16);
  EXPECT_EQ(back.compass.timing.latency, -0.05);
  EXPECT_TRUE(back.drive.equal_wheel_ticks);
  EXPECT_EQ(back.slip.unit, SlipRateUnit::kPerMetre);
  // Doubles survive text exactly.
  EXPECT_EQ(scenario_from_json(json::parse(j.dump())).robot.actual.diameter_left, s.robot.actual.diameter_left);
}

TEST(ScenarioJson, AbsentKeysKeepTheDefaults) {
  const Scenario s = scenario_from_json(json{{"drive", {{"speed", 0.5}}}});
  EXPECT_EQ(s.drive.speed, 0.5);
  EXPECT_EQ(s.drive.turn_rate, Scenario{}.drive.turn_rate);
  EXPECT_EQ(s.name, "custom");
}

TEST(ScenarioJson, PresetKeyStartsFromThatPreset) {
  const Scenario s = scenario_from_json(json{{"preset", "corridor"}, {"motion", {{"distance", 5.0}}}});
  EXPECT_EQ(s.name, "corridor");
  EXPECT_EQ(s.motion.distance, 5.0);
  EXPECT_EQ(s.encoders.timing.rate, 4.0);
  expect_input_error([] { scenario_from_json(json{{"preset", "nope"}}); }, {"preset", "nope"});
}

TEST(ScenarioJson, UnknownKeyIsRejectedWithItsName) {
  expect_input_error(
      [] {
        scenario_from_json(json{{"compass", {{"resolutoin", 0.1}}}});
      },
      {"unknown key", "compass.resolutoin"});
  expect_input_error([] { scenario_from_json(json{{"sped", 1.0}}); }, {"unknown key", "sped"});
  expect_input_error(
      [] {
        scenario_from_json(json{{"compass", {{"zones", json::array({{{"shape", "circle"}, {"min", {0, 0}}}})}}}});
      },
      {"compass.zones[0].min"});
}

TEST(ScenarioJson, WrongTypeIsRejectedWithTheKeyAndTheExpectedType) {
  expect_input_error(
      [] {
        scenario_from_json(json{{"drive", {{"speed", "fast"}}}});
      },
      {"drive.speed", "expected a number", "string"});
  expect_input_error(
      [] {
        scenario_from_json(json{{"motion", {{"runs", 2.5}}}});
      },
      {"motion.runs", "expected an integer"});
  expect_input_error([] { scenario_from_json(json{{"start", {1.0, 2.0}}}); }, {"start", "3 numbers"});
  expect_input_error([] { scenario_from_json(json{{"laser", true}}); }, {"laser", "expected an object"});
  expect_input_error(
      [] {
        scenario_from_json(json{{"encoders", {{"enabled", 1}}}});
      },
      {"encoders.enabled", "true or false"});
  expect_input_error(
      [] {
        scenario_from_json(json{{"world", {{"kind", "cave"}}}});
      },
      {"world.kind", "cave", "corridor"});
}

TEST(ScenarioJson, InvalidValuesAreInputErrorsNamingTheField) {
  expect_input_error([] { scenario_from_json(json{{"drive", {{"speed", -1.0}}}}); }, {"drive.speed", "> 0"});
  expect_input_error([] { scenario_from_json(json{{"laser", {{"dropout", 1.5}}}}); }, {"laser.dropout"});
}

TEST(ScenarioJson, LoadsAFileAndReportsSyntaxErrorsWithTheLine) {
  locbench::testing::ScratchDir dir;
  {
    std::ofstream(dir.file("ok.json")) << R"({"preset": "ideal", "motion": {"distance": 2.0}})";
    std::ofstream(dir.file("bad.json")) << "{\n  \"drive\": {\n    \"speed\": ,\n  }\n}\n";
  }
  EXPECT_EQ(load_scenario(dir.file("ok.json")).motion.distance, 2.0);
  try {
    load_scenario(dir.file("bad.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3u);
    EXPECT_EQ(e.file(), dir.file("bad.json").string());
  }
  expect_input_error([&] { load_scenario(dir.file("missing.json")); }, {"cannot open"});
}

TEST(Validate, NamesTheFirstInvalidField) {
  Scenario s;
  s.physics.step = 0.0;
  try {
    validate(s);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("physics.step"), std::string::npos);
  }
  s = Scenario{};
  s.slip.straight.magnitude_min = 0.5;
  s.slip.straight.magnitude_max = 0.2;
  EXPECT_THROW(validate(s), UsageError);
}

}  // namespace
}  // namespace locbench::sim
