#include "algorithms/calibration/umbmark_improved.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/units.h"

namespace locbench::calibration {

ImprovedUmbmarkResult improved_umbmark(const UmbmarkInput& in, const ImprovedUmbmarkOptions& options) {
  check_umbmark_input(in, true);
  if (!(options.measured_leg_length >= 0.0) || !std::isfinite(options.measured_leg_length)) {
    throw std::invalid_argument("improved UMBmark: measured_leg_length must be ≥ 0");
  }
  ImprovedUmbmarkResult r;
  r.centroids = umbmark_centroids(in.runs);
  const auto& c = r.centroids;
  const double side = in.side_length;
  const double k = -4.0 * side;

  // Step 1 (2.3a or 2.3b) and step 7 (2.6a or 2.6b), in radians.
  const double beta_x = (c.cw.x() - c.ccw.x()) / k, alpha_x = (c.cw.x() + c.ccw.x()) / k;
  const double beta_y = (c.cw.y() + c.ccw.y()) / k, alpha_y = (c.cw.y() - c.ccw.y()) / k;
  switch (options.angles) {
    case UmbmarkAngleFormula::kX:
      r.beta = beta_x;
      r.alpha = alpha_x;
      break;
    case UmbmarkAngleFormula::kY:
      r.beta = beta_y;
      r.alpha = alpha_y;
      break;
    case UmbmarkAngleFormula::kMean:
      r.beta = 0.5 * (beta_x + beta_y);
      r.alpha = 0.5 * (alpha_x + alpha_y);
      break;
  }

  // Step 2 (2.4): R = (L/2)/sin(β/2), via the curvature. The chord is L as published, or the
  // tape-measured leg (extension).
  const double chord = options.measured_leg_length > 0.0 ? options.measured_leg_length : side;
  const double curvature = 2.0 * std::sin(r.beta / 2.0) / chord;
  r.radius = curvature != 0.0 ? 1.0 / curvature : std::numeric_limits<double>::infinity();
  const double b = in.nominal.wheelbase;
  if (std::abs(r.beta) >= kPi / 2.0 || std::abs(curvature) * b / 2.0 >= 1.0) {
    throw std::invalid_argument("improved UMBmark: β = " + std::to_string(to_deg(r.beta)) +
                                "° per leg is beyond what eq. 2.4–2.5 describe (|β| < 90°, "
                                "|R| > B/2); check the units of the return errors");
  }
  // Step 3 (2.5).
  r.E_d = (1.0 + curvature * b / 2.0) / (1.0 - curvature * b / 2.0);

  // Step 4 (2.18–2.23). β·R → chord as β → 0: (chord/2)·β/sin(β/2).
  r.radius_left = r.radius - b / 2.0;
  r.radius_right = r.radius + b / 2.0;
  const double beta_r = std::abs(r.beta) < 1e-8 ? chord : (chord / 2.0) * r.beta / std::sin(r.beta / 2.0);
  r.arc_left = beta_r - r.beta * b / 2.0;   // β·(R − B/2)
  r.arc_right = beta_r + r.beta * b / 2.0;  // β·(R + B/2)
  r.c_L = r.arc_left / static_cast<double>(in.leg_ticks_left);
  r.c_R = r.arc_right / static_cast<double>(in.leg_ticks_right);

  // Step 5 (2.24–2.25): D = c·n·C_e/π.
  const double counts_per_rev = in.encoder.counts_per_wheel_rev();
  r.D_L = r.c_L * counts_per_rev / kPi;
  r.D_R = r.c_R * counts_per_rev / kPi;

  // Step 6 (2.9, 2.14, 2.26): τ = τ_n·D_a/D_n, Δα₂ = τ_n − τ.
  const double tau_n = kPi / 2.0;
  const double d_n = in.nominal.mean_diameter();
  r.D_a = 0.5 * (r.D_L + r.D_R);
  r.tau = tau_n * r.D_a / d_n;
  r.delta_alpha2 = tau_n - r.tau;

  // Steps 8–10 (2.17, 2.27, 2.2).
  r.delta_alpha1 = r.alpha - r.delta_alpha2;
  if (std::abs(r.alpha) >= tau_n || std::abs(r.delta_alpha1) >= tau_n) {
    throw std::invalid_argument("improved UMBmark: α = " + std::to_string(to_deg(r.alpha)) +
                                "°, Δα₁ = " + std::to_string(to_deg(r.delta_alpha1)) +
                                "°: beyond 90°; check the units of the return errors");
  }
  r.E_b = tau_n / (tau_n - r.delta_alpha1);
  r.B_actual = r.E_b * in.nominal.wheelbase;

  // Step 11 (2.16).
  r.E_o = r.D_a / d_n;
  r.corrected = {r.D_L, r.D_R, r.B_actual};
  return r;
}

}  // namespace locbench::calibration
