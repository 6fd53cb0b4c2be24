// The thesis's improved UMBmark (eq. 2.16–2.27) pinned on hand-computed cases, and what its E_o
// really is when N_L, N_R are the counts the robot was commanded from its nominal model.
#include "algorithms/calibration/umbmark_improved.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/units.h"
#include "tests/core/umbmark_inputs.h"

namespace locbench::calibration {
namespace {

constexpr auto kCw = UmbmarkDirection::kClockwise;
constexpr auto kCcw = UmbmarkDirection::kCounterClockwise;

// The LabMate's 4 m square: c_n = π·0.15/1000 = 4.712388980e-4 m/tick, a 4 m leg is
// round(8488.26) = 8488 counts. Centroids cw (−0.30, −0.35), ccw (0.10, −0.10).
UmbmarkInput labmate_case() { return testing::labmate_square(8488, {{kCw, -0.30, -0.35}, {kCcw, 0.10, -0.10}}); }

TEST(ImprovedUmbmark, HandComputedCaseFollowsEquations2_16To2_27) {
  // 1) β = (−0.30 − 0.10)/(−16) = 0.025 rad                                          (2.3a)
  // 2) R = 2/sin(0.0125) = 160.0041667 m                                               (2.4)
  // 3) E_d = 160.1741667/159.8341667 = 1.002127205                                     (2.5)
  // 4) R_L = R − 0.17 = 159.8341667, R_R = 160.1741667                         (2.18–2.19)
  //    L_L = β·R_L = 3.995854169, L_R = β·R_R = 4.004354169 m (β·R = 4.000104169)  (2.20–2.21)
  //    c_L = L_L/8488 = 4.707650999e-4, c_R = 4.717665137e-4 m/tick             (2.22–2.23)
  // 5) D_L = c_L·1000/π = 0.1498491854, D_R = 0.1501679453 m                   (2.24–2.25)
  // 6) D_a = 0.1500085653 m; τ = 90°·D_a/D_n = 1.570886023 rad                    (2.9, 2.14)
  //    Δα₂ = τ_n − τ = −8.969605e-5 rad                                                (2.26)
  // 7) α = (−0.30 + 0.10)/(−16) = 0.0125 rad                                          (2.6a)
  // 8) Δα₁ = α − Δα₂ = 0.01258969605 rad                                               (2.17)
  // 9) E_b = 90°/(90° − Δα₁) = 1.008079606                                             (2.27)
  // 10) B_actual = 0.3427470661 m                                                        (2.2)
  // 11) E_o = D_a/D_n = 1.000057102                                                     (2.16)
  const ImprovedUmbmarkResult r = improved_umbmark(labmate_case());
  EXPECT_NEAR(r.beta, 0.025, 1e-15);
  EXPECT_NEAR(r.radius, 160.0041667, 1e-7);
  EXPECT_NEAR(r.E_d, 1.002127205, 1e-9);
  EXPECT_NEAR(r.radius_left, 159.8341667, 1e-7);
  EXPECT_NEAR(r.radius_right, 160.1741667, 1e-7);
  EXPECT_NEAR(r.arc_left, 3.995854169, 1e-9);
  EXPECT_NEAR(r.arc_right, 4.004354169, 1e-9);
  EXPECT_NEAR(r.c_L, 4.707650999e-4, 1e-13);
  EXPECT_NEAR(r.c_R, 4.717665137e-4, 1e-13);
  EXPECT_NEAR(r.D_L, 0.1498491854, 1e-10);
  EXPECT_NEAR(r.D_R, 0.1501679453, 1e-10);
  EXPECT_NEAR(r.D_a, 0.1500085653, 1e-10);
  EXPECT_NEAR(r.tau, 1.570886023, 1e-9);
  EXPECT_NEAR(r.delta_alpha2, -8.969605e-5, 1e-11);
  EXPECT_NEAR(r.alpha, 0.0125, 1e-15);
  EXPECT_NEAR(r.delta_alpha1, 0.01258969605, 1e-11);
  EXPECT_NEAR(r.E_b, 1.008079606, 1e-9);
  EXPECT_NEAR(r.B_actual, 0.3427470661, 1e-10);
  EXPECT_NEAR(r.E_o, 1.000057102, 1e-9);
  EXPECT_NEAR(r.corrected.diameter_left, r.D_L, 0.0);
  EXPECT_NEAR(r.corrected.wheelbase, r.B_actual, 0.0);
}

TEST(ImprovedUmbmark, EoIsTheSideOverTheCommandedCountsNotAMeasurement) {
  // D_a = (L_L + L_R)/(2N)·n·C_e/π = β·R/N·n·C_e/π, and β·R = L·(β/2)/sin(β/2) ≈ L(1 + β²/24):
  // E_o = L/(N·c_n)·(β/2)/sin(β/2) = 4/(8488·4.712388980e-4)·1.0000260 = 1.0000311·1.0000260.
  // Whatever the return errors say, E_o only reflects how N was rounded from L/c_n.
  const double rounding = 4.0 / (8488 * kPi * 0.15 / 1000.0);
  EXPECT_NEAR(rounding, 1.0000310593, 1e-10);
  for (const double x_ccw : {0.10, 0.30, -0.20}) {
    UmbmarkInput in = labmate_case();
    in.runs[1].x_error = x_ccw;
    const auto r = improved_umbmark(in);
    EXPECT_NEAR(r.E_o, rounding * (r.beta / 2.0) / std::sin(r.beta / 2.0), 1e-12) << "x_ccw " << x_ccw;
  }
}

TEST(ImprovedUmbmark, EqualsClassicUmbmarkWithEsFromTheLegCountsAndAlphaLessDeltaAlpha2) {
  // With N_L = N_R: D_L/D_a = 2·L_L/(L_L + L_R) = (R − B/2)/R = 2/(E_d + 1), i.e. classic's c_L
  // (2.12); the improved method is classic UMBmark with E_s := E_o and α := α − Δα₂.
  const auto r = improved_umbmark(labmate_case());
  EXPECT_NEAR(r.D_L / r.D_a, 2.0 / (r.E_d + 1.0), 1e-12);
  EXPECT_NEAR(r.D_R / r.D_a, 2.0 / (1.0 / r.E_d + 1.0), 1e-12);
  EXPECT_NEAR(r.E_b, (kPi / 2.0) / (kPi / 2.0 - (r.alpha - kPi / 2.0 * (1.0 - r.E_o))), 1e-12);
}

TEST(ImprovedUmbmark, MirrorImageForALargerLeftWheel) {
  // β = −0.025: R = −160.0041667, E_d = 1/1.002127205, and the left wheel's arc is the longer
  // one: L_L = β(R − B/2) = 4.004354169, L_R = 3.995854169 (the thesis's step 2 assumes
  // D_L < D_R; the signed formulas cover both).
  UmbmarkInput in = labmate_case();
  in.runs = {{kCw, 0.10, -0.35}, {kCcw, -0.30, -0.10}};
  const auto r = improved_umbmark(in);
  EXPECT_NEAR(r.E_d, 1.0 / 1.002127205, 1e-9);
  EXPECT_NEAR(r.arc_left, 4.004354169, 1e-9);
  EXPECT_NEAR(r.arc_right, 3.995854169, 1e-9);
  EXPECT_GT(r.D_L, r.D_R);
}

TEST(ImprovedUmbmark, StraightLegsGiveEqualArcsOfLengthL) {
  // Pure Type A (mirror-image centroids): β = 0 → R = ∞ and β·R → L: L_L = L_R = 4 m.
  UmbmarkInput in = labmate_case();
  in.runs = {{kCw, -0.2, -0.25}, {kCcw, -0.2, 0.25}};
  const auto r = improved_umbmark(in);
  EXPECT_EQ(r.E_d, 1.0);
  EXPECT_NEAR(r.arc_left, 4.0, 1e-15);
  EXPECT_NEAR(r.arc_right, 4.0, 1e-15);
  EXPECT_NEAR(r.E_o, 4.0 / (8488 * kPi * 0.15 / 1000.0), 1e-12);
}

TEST(ImprovedUmbmark, ATapeMeasuredLegMakesEoAMeasurement) {
  // Extension: the true chord of a leg measured with a tape replaces L in 2.4 and 2.20–2.21.
  // Taped 3.96 m (a robot 1% short): E_o ≈ 3.96/4 · 1.0000311 · (1 + β²/24) = 0.990057.
  ImprovedUmbmarkOptions o;
  o.measured_leg_length = 3.96;
  const auto r = improved_umbmark(labmate_case(), o);
  EXPECT_NEAR(r.E_o, 0.99 * 1.0000310593 * (1.0 + 0.025 * 0.025 / 24.0), 1e-8);
}

TEST(ImprovedUmbmark, NeedsTheLegCountsAndBothDirections) {
  UmbmarkInput in = labmate_case();
  in.leg_ticks_left = 0;
  EXPECT_THROW(improved_umbmark(in), std::invalid_argument);
  in = labmate_case();
  in.runs.pop_back();
  EXPECT_THROW(improved_umbmark(in), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::calibration
