// The diagnosis against logs it does not model: datasets/diagnosis/physical_log_generator.h
// simulates a commanded robot at 1 kHz (drive response, scales, process noise) and logs ODOM at
// 10 Hz on an offset clock, TRUEPOS at 10 Hz and a compass printed with few decimals. Each test
// hides one effect and requires the diagnosis to name it, put its parameter where the issue asks,
// and leave nothing unexplained; the null logs must show nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "algorithms/diagnosis/scale_checks.h"
#include "core/units.h"
#include "datasets/diagnosis/physical_log_generator.h"
#include "tests/algorithms/diagnosis/diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

using sim::PhysicalEffects;
using test_support::detected;
using test_support::find_cause;
using test_support::summary;

const Estimate& parameter(const Diagnosis& d, const std::string& id, const std::string& name) {
  const Cause* c = find_cause(d, id);
  if (c == nullptr) throw std::runtime_error("no cause " + id + "\n" + summary(d));
  for (const auto& p : c->parameters) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no parameter " + name + " of " + id + "\n" + summary(d));
}

Diagnosis diagnose(const PhysicalEffects& e, std::uint64_t seed, sim::PhysicalOptions o = {}) {
  return diagnose_log(sim::generate_physical_log(e, seed, o));
}

// `cause` is named, its `name` parameter within `tolerance` of `value`, and nothing is left
// unexplained.
void expect_explained_by(const Diagnosis& d, const std::string& cause, const std::string& name, double value,
                         double tolerance) {
  ASSERT_TRUE(detected(d, cause)) << summary(d);
  EXPECT_NEAR(parameter(d, cause, name).value, value, tolerance) << summary(d);
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

TEST(DiagnosePhysicalLogs, OdometryStampedAQuarterSecondEarlyIsFoundToTwoHundredthsWithNothingLeft) {
  PhysicalEffects e;
  e.odometry_time_offset = -0.25;  // between the 10 Hz samples' multiples only by accident
  const Diagnosis d = diagnose(e, 11);
  ASSERT_TRUE(detected(d, "sensor_time_offset")) << summary(d);
  const Estimate& off = parameter(d, "sensor_time_offset", "offset_s");
  EXPECT_NEAR(off.value, -0.25, 0.02) << summary(d);
  EXPECT_LT(off.lo, off.hi);
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

TEST(DiagnosePhysicalLogs, AnOffsetOfThirteenHundredthsIsFoundThoughNoMultipleOfTheSamplePeriod) {
  PhysicalEffects e;
  e.odometry_time_offset = -0.13;
  expect_explained_by(diagnose(e, 12), "sensor_time_offset", "offset_s", -0.13, 0.02);
}

TEST(DiagnosePhysicalLogs, AVelocityScaleBesideAnOffsetIsFittedJointlyWithAFiniteInterval) {
  PhysicalEffects e;
  e.odometry_time_offset = -0.13;
  e.velocity_scale = 0.97;
  const Diagnosis d = diagnose(e, 13);
  ASSERT_TRUE(detected(d, "sensor_time_offset")) << summary(d);
  ASSERT_TRUE(detected(d, "velocity_scale")) << summary(d);
  EXPECT_NEAR(parameter(d, "sensor_time_offset", "offset_s").value, -0.13, 0.02) << summary(d);
  const Estimate& s = parameter(d, "velocity_scale", "scale");
  EXPECT_NEAR(s.value, 0.97, 0.25 * 0.03) << summary(d);  // within 25% of the effect
  EXPECT_TRUE(std::isfinite(s.lo) && std::isfinite(s.hi) && s.lo < 0.97 + 0.0075 && s.hi > 0.97 - 0.0075) << summary(d);
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

TEST(DiagnosePhysicalLogs, ADriveLagIsNamedAsADriveResponseNotATimeOffset) {
  PhysicalEffects e;
  e.drive_tau = 0.3;
  const Diagnosis d = diagnose(e, 14);
  ASSERT_TRUE(detected(d, "drive_response")) << summary(d);
  EXPECT_FALSE(detected(d, "sensor_time_offset")) << summary(d);
  EXPECT_NEAR(parameter(d, "drive_response", "tau_s").value, 0.3, 0.075) << summary(d);
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

TEST(DiagnosePhysicalLogs, ADistanceScaleThatGrowsWithSpeedIsNamedSpeedDependent) {
  PhysicalEffects e;
  e.velocity_scale = 0.98;
  e.speed_slope = -0.1;  // 0.97 at 0.1 m/s, 0.93 at 0.5 m/s
  expect_explained_by(diagnose(e, 15), "speed_dependent_scale", "slope_s_per_m", -0.1, 0.025);
}

TEST(DiagnosePhysicalLogs, HeavyTailedProcessNoiseIsNamedAndBiasesNoScale) {
  PhysicalEffects e;
  e.heavy_tail_dof = 3.0;
  sim::PhysicalOptions o;
  o.process_noise_xy = 6e-3;
  o.process_noise_theta = 6e-3;
  const Diagnosis d = diagnose(e, 16, o);
  ASSERT_TRUE(detected(d, "heavy_tailed_noise")) << summary(d);
  for (const char* mean :
       {"velocity_scale", "turn_rate_scale", "turn_rate_bias", "sensor_time_offset", "drive_response"}) {
    EXPECT_FALSE(detected(d, mean)) << mean << "\n" << summary(d);
  }
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

// MRCLAM's signature: most windows at the command, some far slower. The generator's stalls have
// random lengths (the diagnosis's model: a fixed one), so the parameters are checked loosely and
// the implied mean distance scale against the path-length ratio computed from the log directly.
TEST(DiagnosePhysicalLogs, StallsAreNamedDriveStallWithTheMeanDistanceScaleOfThePathLengths) {
  PhysicalEffects e;
  e.stall_rate = 0.15;     // per second
  e.stall_duration = 0.4;  // s: ~6% of the time stopped
  const Log log = sim::generate_physical_log(e, 17);
  const Diagnosis d = diagnose_log(log);
  ASSERT_TRUE(detected(d, "drive_stall")) << summary(d);
  EXPECT_NEAR(parameter(d, "drive_stall", "rate_per_s").value, 0.15, 0.06) << summary(d);
  EXPECT_NEAR(parameter(d, "drive_stall", "duration_s").value, 0.4, 0.15) << summary(d);
  const Cause* c = find_cause(d, "drive_stall");
  double offset = 0.0;
  if (const Cause* o = find_cause(d, "sensor_time_offset"); o != nullptr && o->detected)
    offset = o->parameters[0].value;
  const ScaleChecks checks = scale_checks(build_motion_data(log, {}), offset);
  EXPECT_NEAR(c->extra.at("mean_distance_scale").get<double>(), checks.path_length_ratio, 0.02) << summary(d);
  EXPECT_FALSE(detected(d, "velocity_scale")) << summary(d);
  EXPECT_TRUE(d.unexplained.empty()) << summary(d);
}

TEST(DiagnosePhysicalLogs, NullLogsShowNothing) {
  for (std::uint64_t seed : {21, 22, 23}) {
    const Diagnosis d = diagnose({}, seed);
    EXPECT_TRUE(d.detected.empty()) << "seed " << seed << "\n" << summary(d);
    EXPECT_TRUE(d.unexplained.empty()) << "seed " << seed << "\n" << summary(d);
  }
}

// A 2° compass printed the way loggers print it: the lattice must survive the round-off.
void expect_compass_lattice(int decimals, double lattice_offset, std::uint64_t seed) {
  PhysicalEffects e;
  e.compass_step = deg(2.0);
  e.compass_lattice_offset = lattice_offset;
  e.compass_decimals = decimals;
  sim::PhysicalOptions o;
  o.compass = true;
  const Diagnosis d = diagnose(e, seed, o);
  ASSERT_TRUE(detected(d, "compass_quantization")) << decimals << " decimals\n" << summary(d);
  EXPECT_NEAR(parameter(d, "compass_quantization", "step_rad").value, deg(2.0), 1e-4) << summary(d);
  EXPECT_NEAR(parameter(d, "compass_quantization", "offset_rad").value, lattice_offset, 1e-4) << summary(d);
  EXPECT_FALSE(detected(d, "compass_disturbance")) << summary(d);
}

TEST(DiagnosePhysicalLogs, ACompassLatticePrintedWithSixDecimalsIsFound) { expect_compass_lattice(6, 0.0, 31); }
TEST(DiagnosePhysicalLogs, ACompassLatticePrintedWithFourDecimalsIsFound) { expect_compass_lattice(4, 0.0, 32); }
TEST(DiagnosePhysicalLogs, ACompassLatticeWithAnOffsetIsFoundWithItsOffset) { expect_compass_lattice(6, deg(0.5), 33); }

}  // namespace
}  // namespace locbench::diagnosis
