// Classic UMBmark (Borenstein & Feng; thesis eq. 2.3–2.13, 2.15) pinned on hand-computed cases.
#include "baselines/calibration/umbmark_classic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/units.h"
#include "tests/core/umbmark_inputs.h"

namespace locbench::baselines::calibration {
namespace {

constexpr auto kCw = UmbmarkDirection::kClockwise;
constexpr auto kCcw = UmbmarkDirection::kCounterClockwise;

// The LabMate's 4 m square without leg counts. Centroids: cw (−0.30, −0.35), ccw (0.10, −0.10) [m],
// from two runs each.
UmbmarkInput labmate_case() {
  return testing::labmate_square(0,
                                 {{kCw, -0.28, -0.36}, {kCw, -0.32, -0.34}, {kCcw, 0.09, -0.12}, {kCcw, 0.11, -0.08}});
}

TEST(ClassicUmbmark, HandComputedLabmateCaseFollowsEquations2_3To2_13) {
  // β = (x_cw − x_ccw)/(−4L) = (−0.30 − 0.10)/(−16) = 0.025 rad (1.4324°)             (2.3a)
  // α = (x_cw + x_ccw)/(−4L) = (−0.30 + 0.10)/(−16) = 0.0125 rad (0.7162°)            (2.6a)
  // R = (L/2)/sin(β/2) = 2/sin(0.0125) = 2/0.01249967448 = 160.0041667 m              (2.4)
  // E_d = (R + B/2)/(R − B/2) = 160.1741667/159.8341667 = 1.002127205                   (2.5)
  // E_b = 90°/(90° − α) = 1.5707963/(1.5707963 − 0.0125) = 1.008021581                  (2.8)
  // B_actual = 1.008021581 · 0.34 = 0.3427273375 m                                       (2.7)
  // c_L = 2/(E_d + 1) = 2/2.002127205 = 0.9989375277                                     (2.12)
  // c_R = 2/(1/E_d + 1) = 1.0010624723                                                   (2.13)
  // D_a = E_s·D_n = 0.15 m (E_s = 1); D_L = c_L·D_a = 0.1498406292, D_R = 0.1501593708 m (2.9–2.11)
  const ClassicUmbmarkResult r = classic_umbmark(labmate_case());
  EXPECT_NEAR(r.beta, 0.025, 1e-15);
  EXPECT_NEAR(r.alpha, 0.0125, 1e-15);
  EXPECT_NEAR(r.radius, 160.0041667, 1e-7);
  EXPECT_NEAR(r.E_d, 1.002127205, 1e-9);
  EXPECT_NEAR(r.E_b, 1.008021581, 1e-9);
  EXPECT_NEAR(r.B_actual, 0.3427273375, 1e-10);
  EXPECT_NEAR(r.c_L, 0.9989375277, 1e-10);
  EXPECT_NEAR(r.c_R, 1.0010624723, 1e-10);
  EXPECT_NEAR(r.D_a, 0.15, 1e-15);
  EXPECT_NEAR(r.D_L, 0.1498406292, 1e-10);
  EXPECT_NEAR(r.D_R, 0.1501593708, 1e-10);
  // The correction factors keep the mean: c_L + c_R = 2, and c_R/c_L = E_d.
  EXPECT_NEAR(r.c_L + r.c_R, 2.0, 1e-15);
  EXPECT_NEAR(r.c_R / r.c_L, r.E_d, 1e-14);
  EXPECT_NEAR(r.corrected.diameter_left, r.D_L, 1e-15);
  EXPECT_NEAR(r.corrected.diameter_right, r.D_R, 1e-15);
  EXPECT_NEAR(r.corrected.wheelbase, r.B_actual, 1e-15);
  // E_max,syst = |c_cw| = √(0.09 + 0.1225) = 0.4610 m.
  EXPECT_NEAR(r.centroids.e_max_syst, std::sqrt(0.2125), 1e-12);
}

TEST(ClassicUmbmark, TheYFormulasUseTheYCentroids) {
  // β = (y_cw + y_ccw)/(−4L) = (−0.35 − 0.10)/(−16) = 0.028125 rad           (2.3b)
  // α = (y_cw − y_ccw)/(−4L) = (−0.35 + 0.10)/(−16) = 0.015625 rad           (2.6b, corrected:
  //     the text prints x_ccw where y_ccw belongs)
  // kMean averages a and b: β = 0.0265625, α = 0.0140625.
  const auto y = classic_umbmark(labmate_case(), {UmbmarkAngleFormula::kY});
  EXPECT_NEAR(y.beta, 0.028125, 1e-15);
  EXPECT_NEAR(y.alpha, 0.015625, 1e-15);
  const auto m = classic_umbmark(labmate_case(), {UmbmarkAngleFormula::kMean});
  EXPECT_NEAR(m.beta, 0.0265625, 1e-15);
  EXPECT_NEAR(m.alpha, 0.0140625, 1e-15);
}

TEST(ClassicUmbmark, TapeMeasuredScaleSetsTheMeanDiameterOnly) {
  // E_s = 1.01: D_a = 0.1515 m, D_L = 0.9989375277·0.1515 = 0.1513390354,
  // D_R = 1.0010624723·0.1515 = 0.1516609646; E_d, E_b unchanged (2.15 enters only 2.9–2.11).
  UmbmarkInput in = labmate_case();
  in.tape_measure_scale = 1.01;
  const auto r = classic_umbmark(in);
  EXPECT_NEAR(r.D_a, 0.1515, 1e-15);
  EXPECT_NEAR(r.D_L, 0.1513390354, 1e-10);
  EXPECT_NEAR(r.D_R, 0.1516609646, 1e-10);
  EXPECT_NEAR(r.E_d, 1.002127205, 1e-9);
  EXPECT_NEAR(r.E_b, 1.008021581, 1e-9);
}

TEST(ClassicUmbmark, NoTypeBErrorGivesEqualWheelsWithoutDividingByZero) {
  // Mirror-image centroids (pure Type A): β = 0, R = ∞, E_d = 1, c_L = c_R = 1.
  UmbmarkInput in = labmate_case();
  in.runs = {{kCw, -0.2, -0.25}, {kCcw, -0.2, 0.25}};
  const auto r = classic_umbmark(in);
  EXPECT_EQ(r.beta, 0.0);
  EXPECT_EQ(r.radius, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.E_d, 1.0);
  EXPECT_EQ(r.c_L, 1.0);
  EXPECT_EQ(r.c_R, 1.0);
  // α = (−0.4)/(−16) = 0.025 rad → E_b = 1.5707963/1.5457963 = 1.016172894.
  EXPECT_NEAR(r.E_b, 1.016172894, 1e-9);
}

TEST(ClassicUmbmark, ALeftWheelLargerThanTheRightGivesEdBelowOneByTheSameFormula) {
  // Swapping the CW and CCW x centroids flips β: −0.025 rad, R = −160.0041667 m,
  // E_d = (R + B/2)/(R − B/2) = 159.8341667/160.1741667 = 0.997877311 = 1/1.002127205.
  UmbmarkInput in = labmate_case();
  in.runs = {{kCw, 0.10, -0.35}, {kCcw, -0.30, -0.10}};
  const auto r = classic_umbmark(in);
  EXPECT_NEAR(r.beta, -0.025, 1e-15);
  EXPECT_NEAR(r.radius, -160.0041667, 1e-7);
  EXPECT_NEAR(r.E_d, 1.0 / 1.002127205, 1e-9);
  EXPECT_GT(r.D_L, r.D_R);
}

TEST(ClassicUmbmark, UnequalNominalWheelsAreCorrectedPerWheel) {
  // With D_n,L = 0.149, D_n,R = 0.151 the corrected diameters are c·E_s·D_n per wheel:
  // 0.9989375277·0.149 = 0.1488416916 and 1.0010624723·0.151 = 0.1511604333.
  UmbmarkInput in = labmate_case();
  in.nominal = {0.149, 0.151, 0.34};
  const auto r = classic_umbmark(in);
  EXPECT_NEAR(r.corrected.diameter_left, 0.1488416916, 1e-10);
  EXPECT_NEAR(r.corrected.diameter_right, 0.1511604333, 1e-10);
}

TEST(ClassicUmbmark, RejectsMissingDirectionsAndErrorsTooLargeToBeMetres) {
  UmbmarkInput in = labmate_case();
  in.runs.resize(2);  // clockwise only
  EXPECT_THROW(classic_umbmark(in), std::invalid_argument);
  in = labmate_case();
  // Errors in millimetres: β = 400/16 = 25 rad, far beyond a curved leg → rejected.
  in.runs = {{kCw, -300.0, -350.0}, {kCcw, 100.0, -100.0}};
  EXPECT_THROW(classic_umbmark(in), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::baselines::calibration
