// Named presets: the thesis's set-ups with their documented parameters.
#include "datasets/sim/presets.h"

#include <gtest/gtest.h>

#include "core/errors.h"
#include "datasets/sim/scenario_json.h"

namespace locbench::sim {
namespace {

TEST(Presets, ListTheRequiredNamesWithOneLineDescriptions) {
  std::vector<std::string> names;
  for (const auto& p : preset_list()) {
    names.push_back(p.name);
    EXPECT_FALSE(p.description.empty()) << p.name;
    EXPECT_EQ(p.description.find('\n'), std::string::npos);
    EXPECT_EQ(preset(p.name).name, p.name);
  }
  for (const char* required : {"corridor", "umbmark_trilobot", "umbmark_borenstein", "room_laser", "ideal"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
}

TEST(Presets, UnknownNameIsAUsageErrorListingTheKnownOnes) {
  try {
    preset("coridor");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("coridor"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("umbmark_trilobot"), std::string::npos);
  }
}

TEST(Presets, AreValidAndSurviveAJsonRoundTrip) {
  for (const auto& p : preset_list()) {
    const Scenario s = preset(p.name);
    EXPECT_NO_THROW(validate(s)) << p.name;
    EXPECT_EQ(to_json(scenario_from_json(to_json(s))), to_json(s)) << p.name;
  }
}

TEST(Presets, CorridorIsTheThesisTrilobotRun) {
  const Scenario s = preset("corridor");
  const RobotParams r = s.robot.params();
  const NominalModel m = r.nominal_model();
  EXPECT_NEAR(m.meters_per_tick_left, 0.01264, 0.000005);   // C_l = 12.64 mm (§4.3)
  EXPECT_NEAR(m.meters_per_tick_right, 0.01270, 0.000005);  // C_r = 12.70 mm
  EXPECT_DOUBLE_EQ(m.wheelbase, 0.19793);
  EXPECT_NEAR(r.E_o(), 89.03425 / 88.715, 1e-9);
  EXPECT_EQ(s.drive.speed, 0.25);
  EXPECT_EQ(s.encoders.timing.rate, 4.0);
  EXPECT_EQ(s.motion.distance, 10.0);
  EXPECT_EQ(s.world.kind, WorldKind::kCorridor);
  EXPECT_EQ(s.world.corridor_width, 1.8);
  EXPECT_DOUBLE_EQ(s.compass.resolution, deg(2.0));
}

TEST(Presets, UmbmarkPresetsDriveTheirSquares) {
  const Scenario t = preset("umbmark_trilobot");
  EXPECT_EQ(t.motion.kind, MotionKind::kUmbmark);
  EXPECT_EQ(t.motion.side, 1.6);
  EXPECT_EQ(t.motion.runs, 5);
  EXPECT_EQ(t.drive.speed, 0.12);
  const Scenario b = preset("umbmark_borenstein");
  EXPECT_EQ(b.motion.side, 4.0);
  EXPECT_LT(b.robot.params().nominal_model().meters_per_tick_left, 1e-5);  // fine encoders
  EXPECT_NEAR(b.robot.params().E_d(), 1.0025, 1e-12);
  EXPECT_NEAR(b.robot.params().E_b(), 1.01, 1e-12);
}

TEST(Presets, RoomLaserIsThePioneerWithTheLms200AtTheThesisPose) {
  const Scenario s = preset("room_laser");
  EXPECT_EQ(s.world.kind, WorldKind::kRoom);
  EXPECT_DOUBLE_EQ(s.start.x, 2.0);
  EXPECT_DOUBLE_EQ(s.start.y, 1.0);
  EXPECT_DOUBLE_EQ(s.start.theta, deg(46.0));
  EXPECT_EQ(s.drive.speed, 0.2);
  EXPECT_EQ(s.laser.timing.rate, 5.0);
  EXPECT_EQ(s.laser.beams, 181);
  EXPECT_EQ(s.laser.noise, 0.005);
  EXPECT_NEAR(s.robot.params().nominal_model().meters_per_tick_left, 0.0152e-3, 0.00005e-3);
}

TEST(Presets, IdealHasNoNoiseAndTrueEqualsNominal) {
  const Scenario s = preset("ideal");
  const RobotParams r = s.robot.params();
  EXPECT_EQ(r.E_d(), 1.0);
  EXPECT_EQ(r.E_b(), 1.0);
  EXPECT_EQ(r.E_o(), 1.0);
  EXPECT_EQ(s.floor.k_left, 0.0);
  EXPECT_EQ(s.slip.straight.rate, 0.0);
  EXPECT_EQ(s.slip.turn.rate, 0.0);
  EXPECT_EQ(s.compass.noise, 0.0);
  EXPECT_EQ(s.encoders.timing.jitter, 0.0);
}

}  // namespace
}  // namespace locbench::sim
