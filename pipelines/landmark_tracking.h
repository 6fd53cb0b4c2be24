#pragma once
// Landmark localization on a log: the filters of chapter 4 driven by the log's
// odometry and corrected by range-bearing observations of surveyed landmarks (Probabilistic
// Robotics Table 7.2, known correspondence), scored against the log's ground truth.
//
// Every method predicts with the odometry's steps, cut at the observation times so that each
// observation is used at its own time, and runs the same outlier handling: a Mahalanobis gate
// (NIS > χ²₂(gate_probability) is rejected) and recovery when the gate starves the filter (after
// `starve_after` consecutive rejections the next observation is used ungated, counted as a
// recovery). What differs between methods is the process model:
// - fixed_q, sage_husa, vb_akf: the logged motion with their own Q per `process_period_s`
//   (Q·dt/period per step);
// - adaptive_thesis, adaptive_jacobian: the logged motion with the thesis's per-sample Q
//   (eq. 4.36–4.44, diagonal or full-Jacobian form) of the step's wheel travel;
// - nominal_model, diagnosed_model: a fitted motion model (diagnosis::OdometryModel: velocity and
//   turn scales, turn bias, drive lag, time offset, stalls, k² growth, the white floor) used for
//   both the prediction and the process noise, and its fitted landmark sensor model; noise
//   correlated in time (MethodSetup::motion_structure, LandmarkSensorModel::structure) is carried
//   as Gauss–Markov states of the filter (filters::BiasAugmentedEkf).
#include <map>
#include <vector>

#include "algorithms/diagnosis/landmark_model.h"
#include "algorithms/diagnosis/motion_windows.h"
#include "algorithms/diagnosis/odometry_model.h"
#include "algorithms/filters/bias_augmented_ekf.h"
#include "algorithms/filters/compass_ekf.h"
#include "baselines/filters/fixed_q_ekf.h"
#include "baselines/filters/sage_husa_aekf.h"
#include "baselines/filters/vb_akf.h"
#include "core/log.h"

namespace locbench::experiments::landmarks {

// The landmark sensor a filter assumes: z_r = s(φ)·ρ + range_bias + n_r with the range scale
// s(φ) = range_scale + range_off_axis_linear·φ + range_off_axis·φ² off the sensor's axis,
// z_φ = φ + bearing_bias + n_φ, var n_r = range_sigma² + (range_noise_slope·ρ)², var n_φ =
// bearing_sigma² + (bearing_noise_turn_slope·ω)² (ω the turn rate: the filter takes the odometry's,
// the twin its truth's); an observation logged at t was taken at true time t − time_offset; landmark id's
// true position is the surveyed one plus landmark_shift[id].
// Noise correlated in time: the share of a channel's variance that is an AR(1) process common to
// all landmarks, with correlation time time_s (share 0: white noise).
struct NoiseCorrelation {
  double share = 0.0;
  double time_s = 0.0;
};

// Residuals far out in their tails and how they cluster: windows whose standardized residual is
// beyond kLargeResidualSigmas, their share of the summed squares, the fraction of them negative,
// and the mean length of their runs (a run starts at such a window and goes on over adjacent
// windows beyond kRunResidualSigmas with the same sign). Reported, not drawn: independent
// Student-t tails give runs of about one window and half of them negative.
inline constexpr double kLargeResidualSigmas = 4.0;
inline constexpr double kRunResidualSigmas = 2.0;
struct LargeResidualRuns {
  std::size_t windows = 0;
  double share_of_squares = 0.0;
  double negative_fraction = 0.0;
  double mean_run_windows = 0.0;
};
// `z`: standardized residuals in time order; `adjacent[k]`: window k follows window k − 1 without a
// gap. Throws UsageError when the two differ in size.
LargeResidualRuns large_residual_runs(const std::vector<double>& z, const std::vector<bool>& adjacent);

// The time correlation of a motion model's window residuals (x, y, θ), standardized by their
// model variance: heading error that persists over many windows is what makes long-horizon drift.
struct MotionNoiseStructure {
  NoiseCorrelation x, y, theta;
  LargeResidualRuns along_large;  // of the along-track residuals (stalls: negative, in runs)
  // The probability that a drive stall goes on into the next window, P(stall in k + 1 | stall in k):
  // real stalls come in runs of several windows (the robot pushing against something), which the
  // diagnosis's mixture, independent per window, does not draw (0: not measured; the twin then
  // draws stalls independently). Carried by the twin only.
  double stall_persistence = 0.0;
  // A turn-rate bias that moves along the log: the spread [rad/s] of the heading residual's rate
  // between blocks of kLevelBlockS beyond what the windows' own noise (white and correlated, as
  // fitted) puts there; the twin draws a new bias per block (0: not measured or none). Carried by
  // the twin only.
  double turn_bias_spread = 0.0;
  // A noise level that moves along the log: the spread of ln σ of the standardized window residuals
  // (x, y, θ) between blocks of kLevelBlockS beyond their sampling spread (noise_level_spread) —
  // episodes of harder driving, as the sensor's NoiseStructure::range_level_sigma is for its noise.
  // The twin draws one level per block, common to the three components, e^(s_c·N(0, 1)) (0: none).
  // Carried by the twin only.
  Eigen::Vector3d level_spread = Eigen::Vector3d::Zero();
  bool correlated() const { return x.share > 0.0 || y.share > 0.0 || theta.share > 0.0; }
};

// The sensor noise's structure beyond white noise, measured on residuals against the truth:
// biases that differ between landmarks (drawn anew per landmark, normal with these spreads) and a
// time correlation common to all landmarks (after each landmark's bias is removed).
struct NoiseStructure {
  NoiseCorrelation range_correlation, bearing_correlation;
  double range_landmark_sigma = 0.0;    // [m]
  double bearing_landmark_sigma = 0.0;  // [rad]
  // Noise levels that vary along the log: the spread of ln σ between blocks of kLevelBlockS
  // (noise_level_spread), drawn anew per block by the twin.
  double range_level_sigma = 0.0, bearing_level_sigma = 0.0;
  // Gross outliers (a misread barcode, a reflection): the share of observations with a range or
  // bearing residual beyond kOutlierSigmas robust σ, less the share the sensor's own noise
  // (normal, or Student-t with its dof) puts there; the twin draws an outlier with this
  // probability, its residual resampled from `outliers` (range in units of the sensor's σ(ρ),
  // bearing in rad). Filters meet them through their gate.
  double outlier_rate = 0.0;
  std::vector<Eigen::Vector2d> outliers;
};
inline constexpr double kOutlierSigmas = 5.0;

struct LandmarkSensorModel {
  double range_scale = 1.0, range_bias = 0.0, bearing_bias = 0.0;
  double range_off_axis_linear = 0.0, range_off_axis = 0.0;  // [1/rad], [1/rad²]
  double field_of_view = kPi;                                // [rad]: s(φ) held at its value beyond ±field_of_view
  double range_scale_at(double phi) const {
    return diagnosis::off_axis_range_scale(range_scale, range_off_axis_linear, range_off_axis, field_of_view, phi);
  }
  double range_sigma = 0.1, bearing_sigma = 0.05, range_noise_slope = 0.0;
  double bearing_noise_turn_slope = 0.0;  // [s]
  double time_offset = 0.0;
  std::map<int, Eigen::Vector2d> landmark_shift;
  // Student-t noise with this many degrees of freedom (0: normal): the update is made robust by
  // one reweighting step of the t likelihood, R ← R·max(1, (ν + NIS)/(ν + 2)) with the NIS under R
  // (Roth, Özkan and Gustafsson, "A Student's t filter for heavy tailed process and measurement
  // noise", ICASSP 2013).
  double dof = 0.0;
  // Twins draw all of it (landmark_twin.h). The fitted-model filters carry the time-correlated
  // share as range and bearing biases of their state (filters::BiasAugmentedEkf) and take only the
  // rest as white noise; every other filter assumes white noise and discounts correlated errors
  // through its tuned R scale. Per-landmark biases stay in the white noise of every filter.
  NoiseStructure structure;
  bool correlated() const {
    return structure.range_correlation.share > 0.0 || structure.bearing_correlation.share > 0.0;
  }
};

struct Observation {
  double t = 0.0;  // logged
  int id = 0;
  double range = 0.0, bearing = 0.0;
};

// One span of one log: what every filter sees and is scored against.
struct TrackingData {
  std::string log;
  double from = 0.0, to = 0.0;            // true (reference) time
  diagnosis::MotionData motion;           // the span's odometry steps (logged time) and its truth
  std::vector<Observation> observations;  // of map landmarks, logged time order
  std::map<int, Eigen::Vector2d> map;
  double wheelbase = 0.0;
  std::size_t other_robot_observations = 0;  // observations of subjects not in the map, left out
};

// The span [from, to] of `log` (true time). Throws InputError (naming the log) when the log has
// no landmark map, no observation of a map landmark in the span, or no usable odometry or truth.
TrackingData tracking_data(const Log& log, double from, double to, double wheelbase);

// A sensor's noise measured on a span: σ_r and σ_φ = 1.4826·MAD of the range and bearing
// residuals against the truth under `sensor`'s deterministic part (scale, off-axis scale, biases,
// time offset, moved landmarks; for the nominal sensor the raw residuals) (robust: the residuals have heavy
// tails), and their structure: the spread of the per-landmark medians (1.4826·MAD over landmarks
// with ≥ 10 observations) and the time correlation of the residuals less their landmark's median
// (fit_noise_correlation), and how the noise level varies along the span (noise_level_spread; the
// range residuals in units of `sensor`'s own σ(ρ) = √(range_sigma² + (range_noise_slope·ρ)²)).
// Leaves `sensor`'s other fields;
// throws InputError with fewer than 20 residuals.
LandmarkSensorModel measured_sensor_noise(const TrackingData& data, LandmarkSensorModel sensor);

// How much a noise level varies along a log: blocks of kLevelBlockS with ≥ kMinLevelBlockResiduals
// residuals each give σ_b = 1.4826·MAD; the spread is √max(0, var ln σ_b − mean 1.35/n_b), the
// variance between blocks less what sampling alone gives (the MAD's σ estimate from n values has
// var ln σ̂ ≈ 1.35/n for normal residuals). 0 with fewer than 3 such blocks.
inline constexpr double kLevelBlockS = 60.0;
inline constexpr std::size_t kMinLevelBlockResiduals = 20;
double noise_level_spread(const std::vector<double>& t, const std::vector<double>& r);

// The block lengths [s] and the fewest blocks per length of fit_noise_correlation.
inline constexpr double kCorrelationScales[] = {2.0, 5.0, 10.0, 30.0};
inline constexpr std::size_t kMinBlocksPerScale = 8;
inline constexpr std::size_t kMinFramePairs = 20;

// The time correlation of residuals r at times t (sorted), as a white part plus a shared
// Gauss–Markov part, ρ(Δt) = s·e^(−Δt/τ). It is fitted to what a filter averaging observations
// sees: the variance of the residuals' means over blocks of 2, 5, 10 and 30 s (residuals clipped at
// 4 robust σ), relative to their variance. For a block of n observations at spacing g the model
// gives var(mean)/σ² = ((1 − s) + s·S)/n, S = 1 + 2Σ_{k=1}^{n−1}(1 − k/n)a^k, a = e^(−g/τ); (s, τ)
// minimize the squared log ratio of observed to model, summed over the lengths with ≥ 8 blocks of
// ≥ 2 residuals (a grid: s in [0, 1], τ log-spaced from 0.1 s to the longest block, 30 s: a longer
// time is not seen by the blocks; refined around its best).
// (Matched to lag-1 and 20-lag sums before, the fit missed the 5–30 s part: on MRCLAM robot 3 the
// 10 s block means varied 0.42 of the variance against the fitted model's 0.22.)
// Where residuals share a time stamp (several landmarks seen in one camera frame, ≥ 20 degrees
// of freedom among them), the share is not fitted but measured: the common part is the same for
// every residual of a frame, so their spread about the frame's mean is the white part alone
// (s = 1 − pooled within-frame variance / variance), and the blocks fit τ only. (Fitted from the
// blocks alone, the share reached 100% on MRCLAM robots 1 and 4, which leaves a filter that
// carries the correlated part as a state no white noise, and it then rejects 65–75% of the
// observations.)
// No correlation (share 0) with fewer than 40 residuals or 2 usable lengths.
NoiseCorrelation fit_noise_correlation(const std::vector<double>& t, const std::vector<double>& r);

// One step of a model's motion, in true time: the increment (ΔD along the chord, Δθ), the
// model's covariance of it in the robot frame at the step's start (x along, y left, θ), and the
// translation before the stalls' mean loss, which a stall's loss acts on (0: the model has no
// stalls).
struct MotionStep {
  double t0 = 0.0, t1 = 0.0;
  double distance = 0.0, turn = 0.0;
  Matrix3 body_covariance = Matrix3::Zero();
  double stall_distance = 0.0;
};

// The steps of `model` over the span, cut at the observations' true times (`cuts`), its
// increments from diagnosis::predict_window (drive lag, scales, turn bias) with the stalls' mean
// loss φ = rate·duration/(1 + rate·duration) taken off the translation, and its covariance per
// step: the white floor (σ per noise_window_s, scaled by dt/noise_window_s; × ν/(ν − 2) for
// Student-t tails with ν > 2) and the k² growth of eq. 4.36–4.37. The stalls' spread about their
// mean loss is not white: a filter carries it as a state (stall_loss_process).
std::vector<MotionStep> model_motion(const TrackingData& data, const diagnosis::OdometryModel& model,
                                     double noise_window_s, const std::vector<double>& cuts);

// The stall loss a filter carries, the fraction of a step's translation lost beyond its mean, as a
// Gauss–Markov process (σ, τ) whose mean over a window of `window_s` has the variance of the
// diagnosis's stall mixture, p(1 − p)f² (diagnosis::window_stall_odds), and whose adjacent window
// means are correlated as the twin's stall chain: ρ = (q − p)/(1 − p) with q the stall
// persistence (MotionNoiseStructure::stall_persistence). For a process of correlation time τ,
// x = window_s/τ, a window mean has variance σ²·g(x), g(x) = 2(x − 1 + e^(−x))/x², and adjacent means
// correlate (1 − e^(−x))²/(x²·g(x)). Without persistence (q ≤ p) the stalls are a two-state chain
// of their own rate and duration, τ = 1/(rate + 1/duration). σ = 0 for a model without stalls.
filters::GaussMarkovBias stall_loss_process(const diagnosis::OdometryModel& model, double window_s, double persistence);

enum class Method { kFixedQ, kAdaptiveThesis, kAdaptiveJacobian, kSageHusa, kVbAkf, kNominalModel, kDiagnosedModel };
inline constexpr Method kMethods[] = {Method::kFixedQ,        Method::kAdaptiveThesis, Method::kAdaptiveJacobian,
                                      Method::kSageHusa,      Method::kVbAkf,          Method::kNominalModel,
                                      Method::kDiagnosedModel};
const char* to_string(Method m);

// What a method runs with. `knob` is the method's second tuned parameter: the R scale for
// fixed_q, the adaptive models and the fitted models; the forgetting factor b for Sage–Husa and
// ρ for VB-AKF (both estimate R themselves).
struct MethodSetup {
  Method method = Method::kFixedQ;
  double process_scale = 1.0;  // multiplies the method's process noise (Q, Q̂(0), model covariance)
  double knob = 1.0;
  const std::vector<MotionStep>* motion = nullptr;  // the steps it predicts with
  LandmarkSensorModel sensor;
  Vector3 fixed_q_per_s{0.0025, 0.0025, 0.0025};  // fixed_q, Q̂(0) of sage_husa, vb_akf's Q [m²/s, m²/s, rad²/s]
  filters::OdometryNoiseOptions adaptive;         // adaptive_thesis / adaptive_jacobian (form set by the method)
  Vector3 initial_sigma{0.02, 0.02, 0.02};        // P(0) = diag(σ²) at the span's true start [m, m, rad]
  // The fitted model's motion noise correlated in time (fitted models only; none: white), carried
  // as motion-error states of the filter (filters::BiasAugmentedEkf) whose share of each step's
  // covariance is taken out of its white noise; the model's noise window [s].
  MotionNoiseStructure motion_structure;
  double noise_window_s = 1.0;
  // The stall loss the filter carries as a state (stall_loss_process; σ = 0: none). Required
  // for motion steps with a stall distance.
  filters::GaussMarkovBias stall;
  // Noise levels that vary along the log, tracked (fitted models only; 0: not tracked): each
  // channel's R is multiplied by λ = (σ_w / reference)², σ_w the robust σ (1.4826·MAD) of the
  // channel's innovations, standardized by their predicted σ under the untracked R, over the last
  // kLevelBlockS before the observation (≥ kMinLevelBlockResiduals of them; else λ = 1), and the
  // reference the same σ over a whole run at this setting on the tuning part
  // (TrackResult::innovation_sigma). λ is kept within [1/kMaxLevelRatio, kMaxLevelRatio].
  Eigen::Vector2d level_reference = Eigen::Vector2d::Zero();
  // Measure TrackResult::innovation_sigma (a fitted model's reference run; tracking measures it too).
  bool measure_innovation_level = false;
};
inline constexpr double kMaxLevelRatio = 256.0;

struct GatePolicy {
  double gate_probability = 0.999;  // χ²₂ quantile of the Mahalanobis gate
  int starve_after = 10;            // consecutive rejections before an observation is used ungated
  double divergence_error_m = 1.0;  // diverged: position error above this at ≥ 5% of the steps
};

struct TrackResult {
  std::vector<double> t;  // true time of each step end
  std::vector<double> position_error, heading_error, nees;
  std::vector<double> log_det_covariance;  // ln det P at each step
  std::size_t observations = 0, used = 0, gated = 0, recoveries = 0;
  bool finite = true;
  bool diverged = false;
  // The robust σ (1.4826·MAD) of the range and bearing innovations over the run, each standardized
  // by its predicted σ under the untracked R (MethodSetup::level_reference); 0 with < 20, or when
  // neither tracked nor asked for (MethodSetup::measure_innovation_level).
  Eigen::Vector2d innovation_sigma = Eigen::Vector2d::Zero();
  double position_rmse() const;
  double heading_rmse() const;
  double gated_fraction() const;
  // The mean negative log-likelihood of the truth under the filter's Gaussian, ½(NEES + ln det P)
  // per step without the constant (a proper scoring rule: it rewards accuracy and a covariance
  // that matches it, Gneiting and Raftery, JASA 2007); +∞ for a diverged run.
  double log_score() const;
};

// One filter over the span. Throws UsageError for a setup without motion steps.
TrackResult track(const TrackingData& data, const MethodSetup& setup, const GatePolicy& gate);

}  // namespace locbench::experiments::landmarks
