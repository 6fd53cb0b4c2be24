#pragma once
// The twin of a landmark log: a synthetic copy of one span that keeps everything the
// robot was told and when it looked — the logged odometry, the landmark map, the observation
// schedule (frame times and landmarks per frame) — and draws what the world did from a fitted model, so a
// filter can be run on as many copies of the log as wanted and its real result predicted.
//
// One model: the truth is drawn from the diagnosis's own window likelihood, not from a separate
// simulator mapping. Over each diagnosis window w (diagnosis::MotionData::windows) the true motion,
// in the frame of the window's start, is
//   prediction(w) + r,   r_c = √v_c · t_ν  (c = x, y, θ; t_ν Student-t with the model's dof, normal
//                                           when dof = 0; v from diagnosis::window_variance),
// with the prediction of diagnosis::predict_window under the model without stalls, and with
// probability p = 1 − exp(−rate·T) a stall that removes the fraction f = min(duration/T, 1) of its
// translation — the mixture odometry_model.h defines, its stalls drawn as a two-state chain whose
// stationary probability is p and which stays stalled into the next window with the measured
// persistence q (MotionNoiseStructure::stall_persistence; independent windows when q ≤ p). Steps
// between windows (gaps) move as
// predicted, without noise. Inside a window the truth follows the prediction's partial sums with
// the window's noise and stall spread in proportion to time. The truth is stamped in true time:
// logged time − the model's time_offset. A noise level that moves along the log
// (MotionNoiseStructure::level_spread) scales each block's residuals by one draw per block.
//
// Steering (follow_time_s > 0, pose odometry): a logged robot was steered by where it was, so its
// commands replayed open loop walk the twin's robot away from the log's path (on MRCLAM Dataset 6,
// 1.4–3.0 m RMS), and the twin's camera, which sees only what is in reach, loses a third of the
// log's view. With steering each moving window's commands get a correction toward the log's truth
// at the window's start, closing T/follow_time_s of the gap (steer_window in the .cpp); standing
// windows are left alone. The twin's odometry is the steered commands, and its truth is the model
// applied to them plus the drawn residual, as without steering.
//
// The camera keeps the log's frames: each frame (observations sharing a logged time t) looks at
// true time t − the sensor's time_offset, from the twin's pose then, and sees as many landmarks as
// the log's frame did, within the camera's reach the log shows (the widest |bearing| and the
// longest range among its observations): a landmark the log saw where it is in reach, else another
// one in reach drawn at random (none left: fewer). Each observation is of the landmark at its
// surveyed position plus the sensor's landmark_shift, drawn from the sensor model
// (landmark_tracking.h):
//   z_r = range_scale_at(φ)·ρ + range_bias + n_r,  z_φ = φ + bearing_bias + n_φ,
//   n_r = √(range_sigma² + (range_noise_slope·ρ)²) · u_r,
//   n_φ = √(bearing_sigma² + (bearing_noise_turn_slope·ω)²) · u_φ  (ω: the truth's turn rate, ±0.05 s),
// u = √(1 − s)·t_ν + √s·b, with s and b the share and the Gauss–Markov process of the channel's
// NoiseCorrelation (time correlation common to all landmarks; s = 0: white), plus each landmark's
// own range and bearing bias, drawn once per twin from N(0, landmark σ²) (sensor.structure). With
// probability sensor.structure.outlier_rate the observation is a gross outlier instead: its range
// and bearing residuals resampled from sensor.structure.outliers (range in units of σ(ρ)).
// An observation whose true time the twin's truth does not cover is left out.
#include <cstdint>

#include "algorithms/diagnosis/odometry_model.h"
#include "pipelines/landmark_tracking.h"

namespace locbench::experiments::landmarks {

// Fitted (fit_noise_correlation) on the windows of `data` under `model`; the stall persistence
// q = Σ π_k·π_{k+1} / Σ π_k over adjacent windows k, k + 1 that would both show a stall, with π
// their stall posteriors (diagnosis::stall_posteriors), kept within [0, kMaxStallPersistence]; 0 when
// the stalls expected in those windows, Σ π_k, are fewer than kMinStallWindows.
inline constexpr double kMaxStallPersistence = 0.95;
inline constexpr double kMinStallWindows = 5.0;
MotionNoiseStructure fit_motion_noise_structure(const diagnosis::MotionData& data,
                                                const diagnosis::OdometryModel& model);

// A twin of `real` drawn with `seed`, steered toward the log's path with `follow_time_s` (0: the
// logged commands replayed open loop); `structure` correlates its window residuals in time
// (each component √(1 − s)·t_ν + √s·b with b a Gauss–Markov process over the windows' times). Throws InputError (naming
// the log) when the span has no diagnosis window or its truth does not cover the span's start.
TrackingData landmark_twin(const TrackingData& real, const diagnosis::OdometryModel& motion,
                           const LandmarkSensorModel& sensor, std::uint64_t seed,
                           const MotionNoiseStructure& structure = {}, double follow_time_s = 0.0);

// The sensor twin of `real`: the log itself — its odometry and its truth — with the landmark
// observations of its schedule drawn anew from `sensor` from the log's truth, as landmark_twin
// draws them from its own. A method's result on it differs from the real one only where the
// sensor model differs from the log's sensor, so beside the extended twin it tells a forecast
// missed by the motion model (the sensor twin covers the real value) from one missed by the
// sensor model. Throws InputError (naming the log) when the span has no truth.
TrackingData landmark_sensor_twin(const TrackingData& real, const LandmarkSensorModel& sensor, std::uint64_t seed);

}  // namespace locbench::experiments::landmarks
