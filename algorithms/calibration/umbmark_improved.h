#pragma once
// The thesis's improved UMBmark calibration (§2.4, eq. 2.16–2.27), exactly as published:
// E_d from the Type B angle as in UMBmark (2.3–2.5); the arcs the two wheels travel on a curved
// leg (2.18–2.21) over the encoder counts logged on that leg give each wheel's metres per tick
// c_L, c_R (2.22–2.23) and so its diameter (2.24–2.25); their mean D_a gives the turn error
// Δα₂ = τ_n − τ that E_o = D_a/D_n causes (2.14, 2.26), and the rest of the Type A angle,
// Δα₁ = α − Δα₂ (2.17), is put on the wheelbase: E_b = 90°/(90° − Δα₁) (2.27).
//
// Units: SI inside, angles in radians. The thesis writes β and α in degrees (the ×180°/π of
// 2.3/2.6) and converts back with π/180° in 2.20–2.21; both factors are dropped here, and 90°
// is π/2 in 2.26–2.27.
//
// Where the published text is ambiguous, and what is done here:
//  * 2.3a/2.3b, 2.6a/2.6b: "or" — `ImprovedUmbmarkOptions::angles` picks (default the x
//    formulas, 2.3a/2.6a); 2.6b is used as corrected (y_ccw, not the printed x_ccw).
//  * Step 2 assumes D_L < D_R. The formulas are used with their signs instead: β < 0 gives R < 0,
//    E_d < 1 and L_L > L_R, which is the mirror image. R is computed through the curvature
//    2·sin(β/2)/L so that β = 0 (R = ∞) gives E_d = 1 and L_L = L_R = L (the limit of β·R).
//  * B in 2.5 and 2.18–2.19 is the nominal wheelbase (the actual one is what is being sought).
//  * 2.20–2.21 take the arc angle of one leg to be β and the chord of the arc to be the side L
//    (2.4): the robot is assumed to have really driven L. With N_L, N_R the counts commanded
//    from the nominal model (how the thesis's Trilobot and datasets/sim drive), this makes
//    D_a ≈ (L/N)·n·C_e/π a function of the nominal model only, so E_o = D_a/D_n is fixed by that
//    assumption (≈ 1 up to the rounding of N), not measured. `measured_leg_length` (an
//    extension, off by default) replaces L by a tape-measured true chord of a leg.
//  * N_L, N_R: the counts of one straight leg (the thesis does not say which leg or whether
//    averaged; UmbmarkInput holds one pair).
//  * D_n in 2.14 and 2.16 is the mean nominal diameter.
//  * 2.17 adds the two turn errors, a first-order approximation: the true turn is
//    τ_n·E_o/E_b, so α = τ_n(1 − E_o/E_b) while Δα₁ + Δα₂ = τ_n(2 − E_o − 1/E_b); they differ by
//    τ_n(1 − E_o)(1 − 1/E_b).
#include "core/robot_params.h"
#include "core/umbmark_measurements.h"

namespace locbench::calibration {

struct ImprovedUmbmarkOptions {
  UmbmarkAngleFormula angles = UmbmarkAngleFormula::kX;  // 2.3a/2.6a by default
  // Extension, not in the thesis: the true chord of one straight leg measured with a tape [m],
  // used instead of L in 2.4 and 2.20–2.21. 0 = as published (the side L).
  double measured_leg_length = 0.0;
};

struct ImprovedUmbmarkResult {
  UmbmarkCentroids centroids;  // of the input runs, with E_max,syst
  double beta = 0.0;           // Type B angle per leg [rad] (2.3)
  double radius = 0.0;         // R [m] (2.4); ±∞ when β = 0
  double E_d = 1.0;            // (2.5)
  double radius_left = 0.0;    // R_L = R − B/2 (2.18)
  double radius_right = 0.0;   // R_R = R + B/2 (2.19)
  double arc_left = 0.0;       // L_L = β·R_L [m] (2.20)
  double arc_right = 0.0;      // L_R = β·R_R [m] (2.21)
  double c_L = 0.0;            // L_L/N_L [m/tick] (2.22) — a conversion factor, not UMBmark's
  double c_R = 0.0;            // L_R/N_R [m/tick] (2.23)   dimensionless correction factor
  double D_L = 0.0;            // c_L·n·C_e/π [m] (2.24)
  double D_R = 0.0;            // (2.25)
  double D_a = 0.0;            // (D_L + D_R)/2 (2.9)
  double tau = 0.0;            // τ = τ_n·D_a/D_n [rad] (2.14), τ_n = 90°
  double delta_alpha2 = 0.0;   // Δα₂ = τ_n − τ [rad] (2.26)
  double alpha = 0.0;          // Type A angle per 90° turn [rad] (2.6)
  double delta_alpha1 = 0.0;   // Δα₁ = α − Δα₂ [rad] (2.17)
  double E_b = 1.0;            // 90°/(90° − Δα₁) (2.27)
  double B_actual = 0.0;       // E_b·B_nominal (2.2) [m]
  double E_o = 1.0;            // D_a/D_n (2.16)
  WheelGeometry corrected;     // {D_L, D_R, B_actual}: the nominal model to drive with next
};

// Throws std::invalid_argument for input check_umbmark_input rejects (leg counts required), or
// when the angles are too large for 2.5/2.27.
ImprovedUmbmarkResult improved_umbmark(const UmbmarkInput& in, const ImprovedUmbmarkOptions& options = {});

}  // namespace locbench::calibration
