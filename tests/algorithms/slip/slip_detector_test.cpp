// Slip model, disturbance rule, which-wheel logic and corrections (eq. 3.1–3.2, 3.14–3.17) on
// hand-built cases.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algorithms/slip/slip_detector.h"
#include "core/errors.h"

namespace locbench::slip {
namespace {

constexpr double kB = 0.2;  // wheelbase [m]

TEST(SlipDetector, FitsMeanAndPopulationSigma) {
  const std::vector<double> d = {1.0, 2.0, 3.0, 4.0};
  const SlipModel m = fit_slip_model(d);
  EXPECT_DOUBLE_EQ(m.mean, 2.5);
  EXPECT_DOUBLE_EQ(m.stddev, std::sqrt(1.25));  // √(E[x²] − μ²), not the n−1 form
}

TEST(SlipDetector, ThresholdFromProbability) {
  EXPECT_NEAR(slip_threshold(0.95), 1.959964, 1e-6);
  EXPECT_NEAR(slip_threshold(0.90), 1.644854, 1e-6);
  EXPECT_THROW(slip_threshold(1.0), UsageError);
}

TEST(SlipDetector, DisturbanceRule) {
  const WheelDisplacement u{0.1, 0.1};  // θ_C must lie in [−U_L/B, U_R/B] = [−0.5, 0.5]
  EXPECT_FALSE(compass_disturbed(u, 0.5, kB));
  EXPECT_FALSE(compass_disturbed(u, -0.5, kB));
  EXPECT_TRUE(compass_disturbed(u, 0.5001, kB));
  EXPECT_TRUE(compass_disturbed(u, -0.5001, kB));
  EXPECT_FALSE(compass_disturbed(u, 0.55, kB, 0.1));  // margin
  // Standing still: any nonzero compass increment is suspicious.
  EXPECT_TRUE(compass_disturbed({0.0, 0.0}, 0.01, kB));
  // Backwards: the interval is [U_R/B, −U_L/B] = [−0.5, 0.5] again.
  EXPECT_FALSE(compass_disturbed({-0.1, -0.1}, 0.3, kB));
}

TEST(SlipDetector, WhichWheel) {
  // Straight command; the compass turned left (θ_C > θ_E): the left wheel lost travel.
  EXPECT_EQ(slipped_wheel(0.05, 0.0), SlipWheel::kLeft);
  EXPECT_EQ(slipped_wheel(-0.05, 0.0), SlipWheel::kRight);
  EXPECT_EQ(slipped_wheel(0.0, 0.0), SlipWheel::kNone);
  // U_L > U_R (θ_E < 0, Fig. 3.2) and U_L < U_R (Fig. 3.3): same rule.
  EXPECT_EQ(slipped_wheel(-0.05, -0.1), SlipWheel::kLeft);
  EXPECT_EQ(slipped_wheel(0.05, 0.1), SlipWheel::kRight);
  EXPECT_EQ(slipped_wheel(0.15, 0.1), SlipWheel::kLeft);
}

TEST(SlipDetector, CorrectionsOnHandBuiltCases) {
  // Left wheel commanded 0.1 m, really moved 0.08 m; right 0.1 m. True Δθ = 0.02/0.2 = 0.1 rad.
  const WheelDisplacement u{0.1, 0.1};
  const BodyIncrement left = corrected_increment(u, 0.1, kB, SlipWheel::kLeft);
  EXPECT_NEAR(left.rotation, 0.1, 1e-15);                                 // (3.15)
  EXPECT_NEAR(left.distance, (2 * 0.1 - kB * std::tan(0.1)) / 2, 1e-15);  // (3.14)
  EXPECT_NEAR(left.distance, 0.0899666, 1e-7);                            // true ΔD = 0.09; tan vs angle: 0.03 mm
  // Right wheel really moved 0.07 m: Δθ = −0.15 rad.
  const BodyIncrement right = corrected_increment(u, -0.15, kB, SlipWheel::kRight);
  EXPECT_NEAR(right.rotation, -0.15, 1e-15);                                 // (3.17)
  EXPECT_NEAR(right.distance, (2 * 0.1 + kB * std::tan(-0.15)) / 2, 1e-15);  // (3.16)
  EXPECT_NEAR(right.distance, 0.0848865, 1e-7);
  // No slip: eq. 3.12–3.13.
  const BodyIncrement none = corrected_increment({0.1, 0.12}, 0.3, kB, SlipWheel::kNone);
  EXPECT_DOUBLE_EQ(none.distance, 0.11);
  EXPECT_NEAR(none.rotation, 0.1, 1e-15);
  // Wheels reproducing an increment.
  const WheelDisplacement w = wheels_for(left, kB);
  EXPECT_NEAR((w.right - w.left) / kB, 0.1, 1e-15);
  EXPECT_NEAR((w.right + w.left) / 2, left.distance, 1e-15);
}

TEST(SlipDetector, ClassifiesSamples) {
  const SlipModel model{0.0, 0.01};  // σ = 0.01 rad: slip beyond 0.0196 rad
  const SlipDetector det(model, {}, kB);
  // Quiet sample.
  auto d = det.classify({0.1, 0.1}, 0.015);
  EXPECT_EQ(d.status, SampleStatus::kNoSlip);
  EXPECT_DOUBLE_EQ(d.increment.distance, 0.1);
  // Left slip: compass turned left 0.1 rad, encoders say straight.
  d = det.classify({0.1, 0.1}, 0.1);
  EXPECT_EQ(d.status, SampleStatus::kLeftSlip);
  EXPECT_NEAR(d.delta_prime, -0.1, 1e-15);
  EXPECT_NEAR(d.z_score, -10.0, 1e-12);
  EXPECT_NEAR(d.increment.distance, 0.0899666, 1e-7);
  EXPECT_NEAR(d.increment.rotation, 0.1, 1e-15);
  // Right slip.
  d = det.classify({0.1, 0.1}, -0.1);
  EXPECT_EQ(d.status, SampleStatus::kRightSlip);
  // Compass disturbed: outside [−0.5, 0.5]; no correction.
  d = det.classify({0.1, 0.1}, 0.6);
  EXPECT_EQ(d.status, SampleStatus::kCompassDisturbed);
  EXPECT_DOUBLE_EQ(d.increment.distance, 0.1);
  EXPECT_DOUBLE_EQ(d.increment.rotation, 0.0);
  // A lower probability (0.9 → 1.645σ) flags smaller discrepancies.
  SlipDetectorOptions o;
  o.probability = 0.9;
  EXPECT_EQ(SlipDetector(model, o, kB).classify({0.1, 0.1}, 0.018).status, SampleStatus::kLeftSlip);
  EXPECT_EQ(det.classify({0.1, 0.1}, 0.018).status, SampleStatus::kNoSlip);
  // The mean shifts the window: μ = 0.05 → Δθ' = −0.1 is 15σ from it, Δθ' = 0.05 is not.
  const SlipDetector shifted({0.05, 0.01}, {}, kB);
  EXPECT_EQ(shifted.classify({0.1, 0.1}, -0.05).status, SampleStatus::kNoSlip);
}

TEST(SlipDetector, OptionsJson) {
  SlipDetectorOptions o;
  o.probability = 0.9;
  o.disturbance_margin = 0.01;
  nlohmann::json j;
  to_json(j, o);
  SlipDetectorOptions back;
  from_json(j, back);
  EXPECT_EQ(back.probability, 0.9);
  EXPECT_EQ(back.disturbance_margin, 0.01);
  EXPECT_THROW(from_json(nlohmann::json{{"probabilty", 0.9}}, back), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"probability", 1.5}}, back), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"check_disturbance", 1}}, back), UsageError);
  EXPECT_THROW(SlipDetector({0.0, 0.0}, {}, kB), UsageError);
}

}  // namespace
}  // namespace locbench::slip
