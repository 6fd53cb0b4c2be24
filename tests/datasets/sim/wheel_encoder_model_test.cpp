// Encoder quantization (eq. 4.12–4.21): counts are floor(rim travel / C) and the per-sample
// residual (true rim travel − ΔN·C) is triangular on [−C, C] with variance C²/6.
#include "datasets/sim/wheel_encoder_model.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/statistics.h"
#include "sim_test_helpers.h"

namespace locbench::sim {
namespace {

TEST(Wheel, ReportsTheFloorOfTheRimPositionInTicksAlsoBackwards) {
  Wheel w;
  w.meters_per_tick = 0.01264;
  w.q = 3.99;
  EXPECT_EQ(w.count(), 3);
  w.q = -0.01;
  EXPECT_EQ(w.count(), -1);
  w.q = 5.0;
  EXPECT_EQ(w.count(), 5);
  EXPECT_DOUBLE_EQ(w.rim(), 5.0 * 0.01264);
}

TEST(Wheel, ResidualIsRimTravelMinusCountedTravel) {
  // U_act = U + e_k − e_{k+1}: 3 ticks counted for 40 mm of rim travel at C = 12.64 mm.
  EXPECT_NEAR(quantization_residual(0.040, 3, 0.01264), 0.040 - 0.03792, 1e-15);
}

// The corridor Trilobot (C = 12.68 / 12.74 mm true per tick) on a long straight run; encoder
// instants jitter by 30 ms (7.5 mm of travel), so the sub-tick remainders are independent.
class QuantizationResidual : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Scenario s = preset("corridor");
    s.world.kind = WorldKind::kNone;
    s.motion.distance = 400.0;  // 1600 s, 6400 samples
    s.slip = SlipConfig{};
    s.floor = FloorNoiseConfig{};
    result_ = new SimulationResult(simulate(s, 7));
  }
  static void TearDownTestSuite() { delete result_; }

  static std::vector<double> residuals(bool left) {
    const auto& w = result_->wheel_samples;
    const double c = left ? left_c() : result_->robot.meters_per_tick(result_->robot.actual.diameter_right);
    std::vector<double> r;
    // Skip the first and last samples (standing still: remainder exactly 0).
    for (std::size_t i = 2; i + 2 < w.size(); ++i) {
      const double rim = left ? w[i].rim_left - w[i - 1].rim_left : w[i].rim_right - w[i - 1].rim_right;
      const auto n = left ? w[i].count_left - w[i - 1].count_left : w[i].count_right - w[i - 1].count_right;
      r.push_back(quantization_residual(rim, n, c));
    }
    return r;
  }
  static double left_c() { return result_->robot.meters_per_tick(result_->robot.actual.diameter_left); }

  static SimulationResult* result_;
};
SimulationResult* QuantizationResidual::result_ = nullptr;

TEST_F(QuantizationResidual, HasZeroMeanAndVarianceCSquaredOverSix) {
  const double c = left_c();
  const auto r = residuals(true);
  ASSERT_GT(r.size(), 6000u);
  // Standard error of the mean: sqrt(C²/6 / n) ≈ 0.065 mm.
  EXPECT_NEAR(mean(r), 0.0, 4.0 * std::sqrt(c * c / 6.0 / static_cast<double>(r.size())));
  // Var(sample variance) = (μ4 − σ⁴)/n = (2.4 − 1)σ⁴/n → 1.5% relative; allow 6%.
  EXPECT_NEAR(sample_variance(r) / (c * c / 6.0), 1.0, 0.06);
}

TEST_F(QuantizationResidual, StaysWithinPlusMinusOneTick) {
  for (bool left : {true, false}) {
    const double c = left ? left_c() : result_->robot.meters_per_tick(result_->robot.actual.diameter_right);
    const auto r = residuals(left);
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    EXPECT_GT(*lo, -c);
    EXPECT_LT(*hi, c);
    // ...and uses most of that support (a triangle, not a two-valued residual).
    EXPECT_LT(*lo, -0.8 * c);
    EXPECT_GT(*hi, 0.8 * c);
  }
}

TEST_F(QuantizationResidual, HasTheTriangularShape) {
  const double c = left_c();
  const auto r = residuals(true);
  // Kurtosis of the triangular density is 2.4 (a normal's is 3, a uniform's 1.8).
  const double kurtosis = central_moment(r, 4) / std::pow(central_moment(r, 2), 2);
  EXPECT_NEAR(kurtosis, 2.4, 0.1);
  // Triangle: P(|e| < C/2) = 3/4.
  const auto inner = std::count_if(r.begin(), r.end(), [&](double e) { return std::abs(e) < c / 2; });
  EXPECT_NEAR(static_cast<double>(inner) / static_cast<double>(r.size()), 0.75, 0.03);
}

}  // namespace
}  // namespace locbench::sim
