// The ML calibration on simulated robots with known geometry (datasets/sim): it recovers the true
// wheel scales and wheelbase — and a sensor's mounting pose — within the uncertainty it reports.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algorithms/calibration/ml_calibration.h"
#include "core/rng.h"
#include "core/statistics.h"
#include "core/units.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"
#include "pioneer_scenario.h"

namespace locbench::calibration {
namespace {

// A Pioneer-like robot (fine encoders) whose true wheels and wheelbase differ from the nominal
// ones, driving two loops around a 3 m square — one counter-clockwise, one clockwise — on a
// noisy floor (k = 0.002 √m per wheel), without slip, with exact ground truth at the encoder
// instants (10 Hz).
sim::Scenario loop_scenario() {
  sim::Scenario s = test::pioneer_on_a_noisy_floor();
  s.name = "ml_calibration_loops";
  s.robot.nominal = {mm(193.5), mm(193.5), mm(330.0)};
  s.motion.kind = sim::MotionKind::kWaypoints;
  s.motion.waypoints = {{3, 0}, {3, 3}, {0, 3}, {0, 0}, {0, 3}, {3, 3}, {3, 0}, {0, 0}, {2, 1}, {1, 2}, {3, 3}, {0, 0}};
  s.encoders.timing = {true, 10.0, 0.0, 0.0};
  s.truth.rate = 10.0;
  return s;
}

// True values of (left_scale, right_scale, wheelbase): true over nominal metres per tick.
Eigen::Vector3d true_parameters(const RobotParams& robot) {
  return {robot.actual.diameter_left / robot.nominal.diameter_left,
          robot.actual.diameter_right / robot.nominal.diameter_right, robot.actual.wheelbase};
}

TEST(MlCalibrationSim, RecoversWheelScalesAndWheelbaseWithinThreeStandardErrors) {
  const auto sim = sim::simulate(loop_scenario(), 7);
  const CalibrationData data = calibration_data_from_encoders(sim.log);
  const MlCalibrationResult r = calibrate_ml(data);
  const Eigen::Vector3d truth = true_parameters(sim.robot);
  fmt::print("{} samples; noise k = {:.4g} √m, σ_t = {:.3g} m, σ_r = {:.3g} rad; χ²/dof = {:.3f}\n", r.samples_used,
             r.noise(0), r.noise(1), r.noise(2), r.chi2_per_dof);
  for (int i = 0; i < 3; ++i) {
    const CalibratedParameter& p = r.parameters[static_cast<std::size_t>(i)];
    fmt::print("  {:<12} {:.6f} ± {:.6f}  true {:.6f}  nominal {:.6f}  ({:+.2f} σ)\n", p.name, p.value,
               p.standard_error, truth(i), p.nominal, (p.value - truth(i)) / p.standard_error);
    EXPECT_TRUE(p.identifiable) << p.name;
    EXPECT_LE(std::abs(p.value - truth(i)), 3.0 * p.standard_error) << p.name;
  }
}

TEST(MlCalibrationSim, WithASensorFrameReferenceAlsoRecoversTheMountingPose) {
  // A scan matcher on a sensor mounted at (0.12 m, −0.05 m, 0.4 rad): its displacements carry
  // 1 mm / 1 mrad of white noise per sample.
  const Pose2 mount(0.12, -0.05, 0.4);
  const auto sim = sim::simulate(loop_scenario(), 11);
  CalibrationData data = calibration_data_from_encoders(sim.log, {}, std::nullopt, mount);
  ASSERT_TRUE(data.sensor_reference);
  Rng rng(2024);
  for (CalibrationSample& s : data.samples) {
    s.reference = s.reference * Pose2(rng.normal(0.0, 1e-3), rng.normal(0.0, 1e-3), rng.normal(0.0, 1e-3));
  }
  const MlCalibrationResult r = calibrate_ml(data);
  const Eigen::Vector3d odo = true_parameters(sim.robot);
  const double truth[6] = {odo(0), odo(1), odo(2), mount.x, mount.y, mount.theta};
  fmt::print("{} samples; noise k = {:.4g} √m, σ_t = {:.3g} m, σ_r = {:.3g} rad; χ²/dof = {:.3f}\n", r.samples_used,
             r.noise(0), r.noise(1), r.noise(2), r.chi2_per_dof);
  ASSERT_EQ(r.parameters.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    const CalibratedParameter& p = r.parameters[static_cast<std::size_t>(i)];
    fmt::print("  {:<12} {:+.6f} ± {:.6f}  true {:+.6f}  closed form {:+.6f}  ({:+.2f} σ)\n", p.name, p.value,
               p.standard_error, truth[i], p.closed_form, (p.value - truth[i]) / p.standard_error);
    EXPECT_TRUE(p.identifiable) << p.name;
    EXPECT_LE(std::abs(p.value - truth[i]), 3.0 * p.standard_error) << p.name;
  }
}

TEST(MlCalibrationSim, SpreadOverTwentySeedsMatchesTheReportedStandardErrors) {
  const sim::Scenario scenario = loop_scenario();
  std::vector<std::vector<double>> z(3), se(3);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto sim = sim::simulate(scenario, seed);
    const MlCalibrationResult r = calibrate_ml(calibration_data_from_encoders(sim.log));
    const Eigen::Vector3d truth = true_parameters(sim.robot);
    for (int i = 0; i < 3; ++i) {
      const auto& p = r.parameters[static_cast<std::size_t>(i)];
      z[static_cast<std::size_t>(i)].push_back((p.value - truth(i)) / p.standard_error);
      se[static_cast<std::size_t>(i)].push_back(p.standard_error);
    }
  }
  for (int i = 0; i < 3; ++i) {
    const auto& zi = z[static_cast<std::size_t>(i)];
    const double rms_z = rms(zi);
    fmt::print(
        "  param {}: rms of (estimate − truth)/σ over 20 seeds = {:.2f}, mean z = {:+.2f}, "
        "mean σ = {:.3g}\n",
        i, rms_z, mean(zi), mean(se[static_cast<std::size_t>(i)]));
    EXPECT_GT(rms_z, 0.5);
    EXPECT_LT(rms_z, 1.6);
  }
}

}  // namespace
}  // namespace locbench::calibration
