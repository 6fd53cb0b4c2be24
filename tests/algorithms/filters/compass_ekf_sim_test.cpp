// The adaptive-noise compass EKF on simulated corridor runs with known truth.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/filters/compass_ekf.h"
#include "tests/algorithms/filters/corridor_harness.h"

namespace locbench::filters {
namespace {

// The filter whose noise model is the simulator's: k = 0.005 √m, σ = C/√6 of the fine
// encoders, R = (1°)², a small P(0) (the truth at the first sample is known, but P(0) = 0
// would make the NEES of the first samples infinite: the true lateral error is never exactly 0).
CompassEkfOptions matched_options(const sim::Scenario& s) {
  CompassEkfOptions o;
  o.noise.k_left = o.noise.k_right = test::kFloorK;
  o.noise.sigma_left = o.noise.sigma_right = moment_matched_sigma(test::matched_tick(s));
  o.compass_variance = test::kMatchedCompassSigma * test::kMatchedCompassSigma;
  o.initial_covariance = Vector3(1e-6, 1e-6, deg(0.3) * deg(0.3));
  return o;
}

class CompassEkfMatchedCorridor : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    runs_ = new std::vector<sim::SimulationResult>(test::simulate_runs(test::matched_corridor(), kRuns, 7000));
  }
  static void TearDownTestSuite() {
    delete runs_;
    runs_ = nullptr;
  }
  static constexpr int kRuns = 50;
  static constexpr std::size_t kSteps = 150;  // 37.5 s of the 40 s run
  static std::vector<sim::SimulationResult>* runs_;
};
std::vector<sim::SimulationResult>* CompassEkfMatchedCorridor::runs_ = nullptr;

TEST_F(CompassEkfMatchedCorridor, CorrectlyTunedFilterIsConsistent) {
  const CompassEkfOptions o = matched_options(test::matched_corridor());
  const auto mc =
      test::monte_carlo(*runs_, kSteps, [&](double b, const Pose2& start) { return CompassEkf(o, b, start); });
  // 50-run average NEES inside its two-sided 95% χ² interval [2.36, 3.72] at most samples.
  EXPECT_NEAR(mc.nees.bounds.lower, 2.36, 0.01);
  EXPECT_NEAR(mc.nees.bounds.upper, 3.72, 0.01);
  EXPECT_GE(mc.nees.fraction_inside, 0.85);
  EXPECT_NEAR(mc.nees.time_average, 3.0, 0.4);
  EXPECT_GE(mc.nis.fraction_inside, 0.85);
  EXPECT_NEAR(mc.nis.time_average, 1.0, 0.15);
  for (double e : mc.final_errors) {
    EXPECT_TRUE(std::isfinite(e));
    EXPECT_LT(e, 0.1);
  }
}

TEST_F(CompassEkfMatchedCorridor, JacobianFormIsConsistentToo) {
  CompassEkfOptions o = matched_options(test::matched_corridor());
  o.noise.form = OdometryNoiseForm::kJacobian;
  const auto mc =
      test::monte_carlo(*runs_, kSteps, [&](double b, const Pose2& start) { return CompassEkf(o, b, start); });
  EXPECT_GE(mc.nees.fraction_inside, 0.8);  // 0.87; its misses are below (small P(0))
  EXPECT_NEAR(mc.nees.time_average, 3.0, 0.4);
}

TEST_F(CompassEkfMatchedCorridor, OverConfidentProcessNoiseFailsTheNeesCheck) {
  CompassEkfOptions o = matched_options(test::matched_corridor());
  o.process_noise_scale = 0.1;  // claims a tenth of the true odometry noise
  const auto mc =
      test::monte_carlo(*runs_, kSteps, [&](double b, const Pose2& start) { return CompassEkf(o, b, start); });
  EXPECT_LT(mc.nees.fraction_inside, 0.2);
  EXPECT_GT(mc.nees.fraction_above, 0.8);
  EXPECT_GT(mc.nees.time_average, 2.0 * mc.nees.bounds.upper);
  EXPECT_GT(mc.nis.fraction_above, 0.5);
}

TEST_F(CompassEkfMatchedCorridor, OverConservativeProcessNoiseFailsLow) {
  CompassEkfOptions o = matched_options(test::matched_corridor());
  o.process_noise_scale = 5.0;
  const auto mc =
      test::monte_carlo(*runs_, kSteps, [&](double b, const Pose2& start) { return CompassEkf(o, b, start); });
  EXPECT_LT(mc.nees.fraction_inside, 0.5);
  EXPECT_GT(mc.nees.fraction_below, 0.5);
}

TEST(CompassEkfCorridorPreset, PublishedSettingsGiveAFiniteSmallFinalError) {
  // The thesis's setting: Trilobot corridor run with quantized encoders, slip, 2° compass;
  // published k = 0.005 √m, σ = 5.00 mm, R = 2 deg², P(0) = 0.
  const auto runs = test::simulate_runs(sim::preset("corridor"), 10, 100);
  const auto mc = test::monte_carlo(
      runs, 100000, [](double b, const Pose2& start) { return CompassEkf(CompassEkfOptions{}, b, start); });
  for (double e : mc.final_errors) {
    EXPECT_TRUE(std::isfinite(e));
    EXPECT_LT(e, 0.15);  // metres, after 10 m
  }
}

}  // namespace
}  // namespace locbench::filters
