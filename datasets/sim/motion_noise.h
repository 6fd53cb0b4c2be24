#pragma once
// Motion noise of the true robot that no wheel model explains: a white body-velocity noise whose
// integral over `window` seconds has standard deviation sigma_along (x, along the heading),
// sigma_left (y) and sigma_heading (θ) — the diagnosis's noise floor (Diagnosis::noise_sigma_*)
// run forwards. With dof > 0 the noise is heavy-tailed: each consecutive `window` of simulated
// time draws a variance multiplier λ = dof/χ²_dof, so a window's displacement is Student-t with
// `dof` degrees of freedom and scale σ (a Gaussian scale mixture; heavy_tailed_noise.dof).
#include <cmath>

#include "core/pose2.h"
#include "core/rng.h"

namespace locbench::sim {

struct MotionNoiseConfig {
  double window = 1.0;         // [s]
  double sigma_along = 0.0;    // [m] per window
  double sigma_left = 0.0;     // [m] per window
  double sigma_heading = 0.0;  // [rad] per window
  double dof = 0.0;            // Student-t degrees of freedom; 0 = Gaussian

  bool enabled() const { return sigma_along > 0.0 || sigma_left > 0.0 || sigma_heading > 0.0; }
};

class MotionNoise {
 public:
  MotionNoise(const MotionNoiseConfig& c, Rng rng) : c_(c), rng_(rng) {}

  // The noise displacement of one physics step [t, t + dt) in the robot frame (x, y, θ).
  Pose2 step(double t, double dt) {
    if (!c_.enabled()) return {};
    const auto window = static_cast<long long>(std::floor(t / c_.window));
    if (window != window_) {
      window_ = window;
      lambda_ = c_.dof > 0.0 ? c_.dof / rng_.chi_square(c_.dof) : 1.0;
    }
    const double f = std::sqrt(lambda_ * dt / c_.window);
    return {f * c_.sigma_along * rng_.normal(), f * c_.sigma_left * rng_.normal(),
            f * c_.sigma_heading * rng_.normal()};
  }

 private:
  MotionNoiseConfig c_;
  Rng rng_;
  long long window_ = -1;
  double lambda_ = 1.0;
};

}  // namespace locbench::sim
