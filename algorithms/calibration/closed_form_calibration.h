#pragma once
// Censi et al.'s two-step closed-form calibration (IEEE T-RO 2013, §IV), generalised to every
// input kind of calibration_model.h and to samples made of several arcs. It is the starting
// point of the ML estimator (ml_calibration.h) and is reported beside it.
//
// Step 1 — rotation: every kind's rotation over a sample is linear in two coefficients
// (wheels: J21 = −p_L/b, J22 = p_R/b with θ = J21·Σw_L + J22·Σw_R; body: rotation_scale and
// rotation_per_distance; velocity: rv_scale and rv_bias), so they follow from linear least
// squares on the reference rotations (the sensor's rotation equals the robot's).
// Step 2 — translation: given those, the predicted translation is linear in one scale
// (b for wheels — p_L = −J21·b, p_R = J22·b —, translation_scale / tv_scale otherwise):
// o_t = scale · c_i. With a sensor at ℓ, ℓ ∘ s = o ∘ ℓ gives per sample
//   scale·c_i + (R(o_θ) − I)·ℓ_t − R(ℓ_θ)·s_t = 0,
// linear in x = (scale, ℓ_x, ℓ_y, cos ℓ_θ, sin ℓ_θ); minimise Σ‖L_i x‖² subject to
// cos² + sin² = 1 (Censi et al. eq. 22–25). We solve that constrained quadratic by eliminating
// (scale, ℓ_x, ℓ_y) (Schur complement) and taking the smallest eigenvector of the remaining 2×2
// form — the same minimiser as their Lagrange-multiplier quadratic — with the sign making the
// scale positive. Without a sensor to estimate, the scale is a one-dimensional least squares.
#include <array>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/calibration_model.h"

namespace locbench::calibration {

// Which of the six model parameters (odometry 0–2, sensor x, y, θ) are free.
using ParameterMask = std::array<bool, 6>;

struct ClosedFormResult {
  ModelParameters parameters;
  // Condition number of the step-1 least squares (Censi et al. reject data above 75); +∞ when
  // the rotations cannot separate the two coefficients (e.g. straight runs only).
  double rotation_condition = 0.0;
};

// Fixed parameters keep their values from `start`; in directions the data do not determine the
// free ones stay at `start` too (minimum-norm correction). Throws std::invalid_argument for
// data without samples.
ClosedFormResult closed_form_calibration(const CalibrationData& data, const ModelParameters& start,
                                         const ParameterMask& free);

}  // namespace locbench::calibration
