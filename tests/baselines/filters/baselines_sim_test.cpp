// The baseline filters on simulated corridor runs with known truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "baselines/filters/fixed_q_ekf.h"
#include "baselines/filters/sage_husa_aekf.h"
#include "baselines/filters/vb_akf.h"
#include "tests/algorithms/filters/corridor_harness.h"

namespace locbench::baselines::filters {
using locbench::filters::pair_encoder_compass;
namespace {

// The fixed Q matching the matched corridor's floor noise at the cruising travel of 62.5 mm
// per sample: var(w_d) = 2k²U/4, var(w_θ) = 2k²U/B², lateral 0 (θ ≈ 0).
Vector3 matched_fixed_q(double wheelbase) {
  const double kku = test::kFloorK * test::kFloorK * 0.0625;
  return {2.0 * kku / 4.0, 0.0, 2.0 * kku / (wheelbase * wheelbase)};
}
const Vector3 kSmallP0(1e-6, 1e-6, deg(0.3) * deg(0.3));

class BaselinesMatchedCorridor : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    runs_ = new std::vector<sim::SimulationResult>(test::simulate_runs(test::matched_corridor(), 50, 7000));
  }
  static void TearDownTestSuite() {
    delete runs_;
    runs_ = nullptr;
  }
  static std::vector<sim::SimulationResult>* runs_;
};
std::vector<sim::SimulationResult>* BaselinesMatchedCorridor::runs_ = nullptr;

TEST_F(BaselinesMatchedCorridor, CorrectlyTunedFixedQIsConsistent) {
  const auto mc = test::monte_carlo(*runs_, 150, [](double b, const Pose2& start) {
    FixedQEkfOptions o;
    o.process_noise = matched_fixed_q(b);
    o.compass_variance = test::kMatchedCompassSigma * test::kMatchedCompassSigma;
    o.initial_covariance = kSmallP0;
    return FixedQEkf(o, b, start);
  });
  EXPECT_GE(mc.nees.fraction_inside, 0.85);
  EXPECT_NEAR(mc.nees.time_average, 3.0, 0.4);
  EXPECT_GE(mc.nis.fraction_inside, 0.85);
}

TEST_F(BaselinesMatchedCorridor, OverConfidentFixedQFailsTheNeesCheck) {
  const auto mc = test::monte_carlo(*runs_, 150, [](double b, const Pose2& start) {
    FixedQEkfOptions o;
    o.process_noise = 0.1 * matched_fixed_q(b);
    o.compass_variance = test::kMatchedCompassSigma * test::kMatchedCompassSigma;
    o.initial_covariance = kSmallP0;
    return FixedQEkf(o, b, start);
  });
  EXPECT_LT(mc.nees.fraction_inside, 0.2);
  EXPECT_GT(mc.nees.fraction_above, 0.8);
}

TEST_F(BaselinesMatchedCorridor, VbAkfLearnsTheCompassVariance) {
  // Started from the published R = 2 deg², it ends near the true (1°)².
  double sum = 0.0;
  for (const auto& res : *runs_) {
    const NominalModel m = *res.log.nominal_model();
    VbAkfOptions o;
    o.process_noise = matched_fixed_q(m.wheelbase);
    o.initial_covariance = kSmallP0;
    VbAkf f(o, m.wheelbase, res.wheel_samples.front().pose);
    for (const auto& s : pair_encoder_compass(res.log.encoders, res.log.compass, m, 0.125)) {
      f.step(s.u, s.compass);
    }
    sum += f.measurement_variance();
  }
  const double mean = sum / static_cast<double>(runs_->size());
  EXPECT_NEAR(mean / (test::kMatchedCompassSigma * test::kMatchedCompassSigma), 1.0, 0.15);
}

TEST_F(BaselinesMatchedCorridor, SageHusaIsOverConfident) {
  // The estimator's Q̂ collapses: its NEES lies far above the bounds (the thesis's point that
  // its accuracy cannot be trusted).
  const auto mc = test::monte_carlo(
      *runs_, 150, [](double b, const Pose2& start) { return SageHusaAekf(SageHusaOptions{}, b, start); });
  EXPECT_GT(mc.nees.fraction_above, 0.8);
}

TEST(BaselinesCorridorPreset, PublishedSettingsFinalErrors) {
  // The thesis's experiment (Table 4.1): Trilobot corridor run, published settings.
  const auto runs = test::simulate_runs(sim::preset("corridor"), 10, 100);
  auto final_errors = [&](auto make) { return test::monte_carlo(runs, 100000, make).final_errors; };
  const auto fixed = final_errors([](double b, const Pose2& s) { return FixedQEkf(FixedQEkfOptions{}, b, s); });
  const auto vb = final_errors([](double b, const Pose2& s) { return VbAkf(VbAkfOptions{}, b, s); });
  const auto aekf = final_errors([](double b, const Pose2& s) { return SageHusaAekf(SageHusaOptions{}, b, s); });
  SageHusaOptions nofix;
  nofix.positive_definiteness_fix = false;
  const auto unfixed = final_errors([&](double b, const Pose2& s) { return SageHusaAekf(nofix, b, s); });
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_TRUE(std::isfinite(fixed[i]) && fixed[i] < 0.15) << i;
    EXPECT_TRUE(std::isfinite(vb[i]) && vb[i] < 0.15) << i;
    EXPECT_TRUE(std::isfinite(aekf[i]) && aekf[i] < 1.0) << i;
  }
  // The AEKF's spread across runs is wider than the fixed-Q EKF's.
  auto spread = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.back() - v.front();
  };
  EXPECT_GT(spread(aekf), 3.0 * spread(fixed));
  // Without Zhang's fix the estimator diverges on most runs.
  EXPECT_GE(std::count_if(unfixed.begin(), unfixed.end(), [](double e) { return !(e < 1.0); }), 5);
}

}  // namespace
}  // namespace locbench::baselines::filters
