#pragma once
// A diagnosis run back through the simulator: the synthetic twin of a log. The twin replays the
// log's own odometry (replay_commands.h) — so its odometry is the log's — while the truth moves
// as the model says: under the nominal model the commanded motion plus a white noise floor;
// under the extended model also every cause the diagnosis kept (Diagnosis::causes with
// detected == true), mapped to what the simulator does:
//   velocity_scale.scale               → drive.response.velocity_scale
//   speed_dependent_scale.scale_at_0, .slope_s_per_m → drive.response velocity_scale, speed_slope
//                                        (composed with velocity_scale when both are kept)
//   turn_rate_scale.scale, turn_rate_bias.bias_rad_s → drive.response turn_rate_scale, turn_rate_bias
//   drive_response.tau_s               → drive.response.time_constant
//   sensor_time_offset.offset_s        → latency of the replayed odometry sensor (logged − true)
//   wheel_diameter_ratio.E_d, wheelbase_scale.E_b, mean_diameter_scale.E_o → robot.actual
//                                        (D_L' = D_L·E_o·2/(1+E_d), D_R' = D_R·E_o·2E_d/(1+E_d), B' = E_b·B)
//   odometry_noise_growth.k2_m         → floor.k_left = floor.k_right = √k² (eq. 4.16)
//   wheel_slip.rate_per_m, .mean_loss  → slip per metre, loss U[⅔, 4⁄3]·mean_loss
//   heavy_tailed_noise.dof             → motion_noise.dof (Student-t windows, motion_noise.h)
//   encoder_quantization.step_m        → reproduced by the replay itself (the counts as logged)
// Any other kept cause (the compass causes, ids this writer does not know) is listed in the
// scenario's `notes` and in `not_simulated`, never dropped silently.
//
// Noise floor: the white motion noise of each twin (motion_noise, per window of the
// diagnosis's noise_window_s) is fitted by moment matching on the log's own windows (the twin
// replays its odometry, so its reference can be read over exactly those windows): with r the
// nominal-model window residuals (x along, y left, θ) of a log, r_det those of the twin without
// any noise and r_0 those of the twin with every noise but the floor,
//   σ_c² = max(mean((r_real − r_det)_c²) − mean((r_0 − r_det)_c²), 0)       for c = x, y, θ.
// When heavy tails (Student-t windows, ν degrees of freedom) are kept, the variance is infinite
// (ν ≤ 2) or decided by a few windows, so the spread is matched robustly instead: with
// s(·) = 1.4826·MAD, s_c² = max(s(r_real − r_det)² − s(r_0 − r_det)², 0) and the t scale with that
// MAD, σ_c = s_c · z_{0.75} / t_{0.75, ν}. (Moment matching with ν = 1.1 made MRCLAM robot 4's
// extended twin 1.6× farther from the log than the nominal one.) The reference noise of a TRUEPOS reference is
// estimated from its second differences (robust, 1.4826·MAD/√6) and simulated as truth.noise_xy / noise_theta.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/log.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

struct TwinOptions {
  double from = -std::numeric_limits<double>::infinity();  // logged time window of the replay
  double to = std::numeric_limits<double>::infinity();
  std::uint64_t calibration_seed = 1;  // seed of the twin simulated for the floor fit
};

struct CauseMapping {
  std::string id;
  bool simulated = false;
  std::string how;  // what the scenario sets, or why it cannot
};

struct Twin {
  Scenario nominal;
  Scenario extended;
  double time_origin = 0.0;                // logged time = twin time + time_origin
  std::vector<CauseMapping> causes;        // every kept cause, in the diagnosis's order
  std::vector<std::string> not_simulated;  // ids of kept causes the scenario cannot simulate
  // The nominal floor the diagnosis reported (σ_x, σ_y, σ_θ per noise_window_s), beside the
  // moment-matched floors of both twins: an independent check of the fit.
  double diagnosis_floor[3] = {0.0, 0.0, 0.0};
  // The log's residual windows of residual_window_s (twin_residuals.h) the floors were fitted on.
  double residual_window_s = 0.0;
  diagnosis::MotionData residual_windows;
};

// The kept causes mapped onto a scenario (no floor fit: motion_noise sigmas are left at 0):
// `base` gets the causes applied; returns the mapping of every kept cause.
std::vector<CauseMapping> apply_causes(const diagnosis::Diagnosis& d, Scenario& base);

// Both twins of `log` (its reference: TRUEPOS or relations) with fitted noise floors. Throws
// InputError for logs the twin cannot replay (no odometry) or without a position reference.
Twin build_twin(const Log& log, const diagnosis::Diagnosis& d, const TwinOptions& options = {});

// The log a twin scenario gives (simulated TRUEPOS as its reference, whatever the real log's;
// twin_residuals.h reads it at the real log's own windows).
Log twin_log(const Scenario& twin, std::uint64_t seed, const Log& real);

// White noise of a TRUEPOS reference (σ_xy [m], σ_θ [rad]) from the second differences of
// evenly spaced poses: 1.4826·MAD/√6. {0, 0} with fewer than 20 usable triples.
std::pair<double, double> reference_noise(const std::vector<TruePose>& truth);

}  // namespace locbench::sim
