// CARMEN PARAM records for the laser's field of view and resolution set the FLASER bearings.
#include "datasets/io/carmen_laser.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/units.h"
#include "datasets/io/carmen_reader.h"
#include "datasets/io/carmen_writer.h"

namespace locbench::io {
namespace {

const char* kFlaser5 = "FLASER 5 1 1 1 1 1 0 0 0 0 0 0 10.0 host 10.0\n";

TEST(CarmenLaserParams, WithoutFovTheFlaserConventionHolds) {
  const Log log = parse_carmen_log(kFlaser5, "a.clf");
  EXPECT_DOUBLE_EQ(log.laser[0].scan.bearings.front(), -deg(90));
  EXPECT_DOUBLE_EQ(log.laser[0].scan.bearings.back(), deg(90));
}

TEST(CarmenLaserParams, FovAndResolutionInDegreesSetTheBearings) {
  const Log log = parse_carmen_log(
      std::string("PARAM laser_front_laser_fov 100\nPARAM laser_front_laser_resolution 25\n") + kFlaser5, "a.clf");
  const auto& b = log.laser[0].scan.bearings;
  ASSERT_EQ(b.size(), 5u);
  EXPECT_NEAR(b[0], -deg(50), 1e-12);
  EXPECT_NEAR(b[1], -deg(25), 1e-12);
  EXPECT_NEAR(b[4], deg(50), 1e-12);
}

TEST(CarmenLaserParams, FovAloneSpreadsTheBeamsOverIt) {
  const Log log = parse_carmen_log(
      std::string("PARAM laser_front_laser_fov 180\n") + "FLASER 4 1 1 1 1 0 0 0 0 0 0 10.0 host 10.0\n", "a.clf");
  const auto& b = log.laser[0].scan.bearings;
  EXPECT_NEAR(b[0], -deg(90), 1e-12);
  EXPECT_NEAR(b[1], -deg(30), 1e-12);  // 180°/3 steps, not the 4-beam FLASER 45°
  EXPECT_NEAR(b[3], deg(90), 1e-12);
}

TEST(CarmenLaserParams, ResolutionAloneCentresTheBeams) {
  CarmenLaserSetup s;
  s.resolution = deg(0.5);
  const auto b = carmen_bearings(361, s);
  EXPECT_NEAR(b.front(), -deg(90), 1e-12);
  EXPECT_NEAR(b.back(), deg(90), 1e-12);
}

TEST(CarmenLaserParams, InvalidFovIsAnInputErrorNamingTheLine) {
  try {
    parse_carmen_log(std::string("PARAM laser_front_laser_fov -3\n") + kFlaser5, "a.clf");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1u);
    EXPECT_NE(std::string(e.what()).find("field of view"), std::string::npos);
  }
}

TEST(CarmenLaserParams, TheWriterKeepsDeclaredBearingsThroughARoundTrip) {
  const Log log = parse_carmen_log(
      std::string("PARAM laser_front_laser_fov 100\nPARAM laser_front_laser_resolution 25\n") + kFlaser5, "a.clf");
  const Log back = parse_carmen_log(format_carmen_log(log), "b.clf");
  EXPECT_EQ(back.laser[0].scan.bearings, log.laser[0].scan.bearings);
}

}  // namespace
}  // namespace locbench::io
