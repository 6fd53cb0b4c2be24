#pragma once
// The odometry model the diagnosis fits: the log's nominal model with every catalog extension
// that acts on odometry switched on by giving its parameter a value other than the nominal one.
//
// Encoder odometry (eq. 1.1–1.3, with the error factors of eq. 2.1, 2.2, 2.15):
//   c_L' = c_L·E_o·2/(1 + E_d),  c_R' = c_R·E_o·2E_d/(1 + E_d),  B' = E_b·B,
//   U = c'·ΔN,  ΔD = (U_L + U_R)/2,  Δθ = (U_R − U_L)/B'.
// Pose odometry (velocity logs, e.g. a logged velocity command): the robot's velocity follows the
// logged one through a first-order drive response with time constant τ (`drive_tau`, 0 = none):
//   u̇ = (v − u)/τ, so over a step of constant v: ΔD_true = v·Δt + (u₀ − v)·τ·(1 − e^(−Δt/τ)),
// and the same for the turn rate; then
//   ΔD' = (scale + speed_slope·|v|)·ΔD_true,  Δθ' = turn_scale·Δθ_true + turn_bias·Δt
// with v = ΔD/Δt the step's logged speed [m/s] (`speed_slope` [s/m]: a speed-dependent scale).
// Both: the odometry's logged time minus the reference's is `time_offset` (the reference is read
// at t − time_offset).
// Noise of a window's residual r = reference − prediction (x, y along/left of the window's start
// heading, θ): independent normal components with variance
//   v_x = σ_x² + k²W/4,  v_y = σ_y² + k²W/4,  v_θ = σ_θ² + k²W/B²      (eq. 4.36–4.37 summed)
// where W = Σ(|U_L| + |U_R|) is the window's wheel travel and k² (`k2`) the wheel-travel variance
// per metre (eq. 4.16); σ are the nominal model's white noise floor (always fitted).
// Heavy tails (`dof` > 0): each component is Student-t with `dof` degrees of freedom and squared
// scale v instead of normal with variance v (real logs: collisions, reference glitches); dof = 0
// is the normal model.
// Wheel slip (§3.2): with probability p = 1 − exp(−rate·W/2) one wheel (either, equally likely)
// loses the fraction `slip_loss` of one sample's travel, which shifts the residual by
// (−loss·ū/2, 0, ±loss·ū/B) with ū that wheel's mean travel per sample.
// Drive stalls (pose odometry): stall episodes arrive at `stall_rate` per second and stop the
// robot's translation for `stall_duration` seconds; a window of length T holds one with
// probability p = 1 − exp(−rate·T), which then covers only the fraction 1 − f of the predicted
// translation, f = min(duration/T, 1). The residual is the mixture (1 − p)·g(r) + p·g(r + f·t̂)
// with t̂ the predicted translation (x, y); the mean prediction (predict_window, the held-out
// errors) is the translation scaled by 1 − p·f.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "algorithms/diagnosis/motion_windows.h"

namespace locbench::diagnosis {

struct OdometryModel {
  double E_d = 1.0, E_b = 1.0, E_o = 1.0;
  double velocity_scale = 1.0, turn_rate_scale = 1.0, turn_rate_bias = 0.0;
  double speed_slope = 0.0;  // [s/m]
  double drive_tau = 0.0;    // [s]
  double time_offset = 0.0;
  double dof = 0.0;  // Student-t degrees of freedom; 0 = normal
  double sigma_x = 1e-3, sigma_y = 1e-3, sigma_theta = 1e-3;
  double k2 = 0.0;
  double slip_rate = 0.0, slip_loss = 0.0;
  double stall_rate = 0.0;      // [1/s]
  double stall_duration = 0.0;  // [s]
};
// The model as JSON (`"models": {"odometry": …}` in a report; keys carry their units, e.g.
// "sigma_x_m"), and back. Strict: an unknown key, a wrong type or a value out of range →
// UsageError naming the key.
void to_json(nlohmann::json& j, const OdometryModel& m);
void from_json(const nlohmann::json& j, OdometryModel& m);
void validate(const OdometryModel& m);

// A window's mean travel of the left and right wheel per encoder step [m] (the slip mixture's
// shift scales with it).
struct WheelStepMeans {
  double left = 0.0, right = 0.0;
};
WheelStepMeans mean_wheel_steps(const MotionData& d, const MotionWindow& w);

// A window of length `span` [s] under m's stalls: the probability p = 1 − e^(−rate·span) that it
// holds one and the fraction f = min(duration/span, 1) of its translation one takes (0, 0 without
// stalls).
struct StallOdds {
  double p = 0.0;
  double fraction = 0.0;
};
StallOdds window_stall_odds(const OdometryModel& m, double span);

// The expected fraction of a window's translation lost to drive stalls, p·f above (0 when the
// model has none or the odometry is encoder counts).
double expected_stall_loss(const MotionData& d, const MotionWindow& w, const OdometryModel& m);

struct WindowResidual {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();         // reference − prediction
  Eigen::Vector3d variance = Eigen::Vector3d::Ones();  // without slip
  Pose2 prediction;                                    // the model's prediction of the window
  bool valid = false;                                  // the reference covers the (shifted) window
  bool heading_only = false;
};

// The variance (x, y, θ) of window w's residual under m without slip: the floor and the k²
// growth with the window's wheel travel (eq. 4.36–4.37 summed).
Eigen::Vector3d window_variance(const MotionData& d, const MotionWindow& w, const OdometryModel& m);
// The prediction of window w under model m (in the frame of the window's start).
Pose2 predict_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m);
// Pose odometry: the true increments (ΔD, Δθ) of window w's own steps [w.first, w.last) through
// the drive response of time constant `tau` (its state run in from 4τ before the window,
// drive_run_in; the logged increments when tau = 0), two per step into `out`. They depend on τ alone, so the fits
// reuse them while the scales and the bias move (WindowCache::increments).
void drive_increments(const MotionData& d, const MotionWindow& w, double tau, double* out);
// Where window w's drive run-in starts under τ > 0: at t_s = 4τ before w's first step (e^−4 = 2%), or at the first
// of w's contiguous steps when that is later (`clamped`: t_s then does not move with τ). The drive's
// state there is the logged rate interpolated linearly between the midpoints of contiguous steps,
// and the run-in covers only the part of its first step after t_s, so a window's prediction is
// continuous in τ (a run-in from a step's start at that step's rate jumped wherever 4τ crossed a
// step, and the descent in τ needs derivatives). τ ≤ 0: no run-in, step w.first.
struct DriveRunIn {
  std::size_t step = 0;                    // the step holding t_s
  double t = 0.0;                          // t_s
  bool clamped = false;                    // t_s at the start of the contiguous steps
  double v = 0.0, rate = 0.0;              // the interpolated rates at t_s [m/s, rad/s]
  double v_slope = 0.0, rate_slope = 0.0;  // their derivatives in t_s
};
DriveRunIn drive_run_in(const MotionData& d, const MotionWindow& w, double tau);
// predict_window with w's drive_increments under m.drive_tau given (pose odometry; the same
// result bit for bit).
Pose2 predict_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m, const double* increments);
// The reference motion of window w read with the model's time offset.
std::optional<Pose2> reference_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m);
WindowResidual window_residual(const MotionData& d, const MotionWindow& w, const OdometryModel& m);

// Window predictions and reference motions memoized by the parameters they depend on (the
// mean-motion parameters; the time offset): a fit's finite differences over the noise parameters
// and many of its steps reuse them. Tied to one MotionData, which must outlive it and not change.
class WindowCache {
 public:
  explicit WindowCache(const MotionData& d);
  // Per window, empty until computed; valid until the next call for another model.
  std::vector<std::optional<Pose2>>& predictions(const OdometryModel& m);
  // Per window, its reference motion at m's time offset (reference_window; nullopt where the
  // shifted reference does not cover it), computed for every window at once and shared with
  // every copy of this cache (the fits made side by side profile the same offsets); valid until
  // the next call.
  const std::vector<std::optional<Pose2>>& references(const OdometryModel& m);
  // Window wi's drive_increments under τ (pose odometry), memoized by τ; valid until the next call
  // with another τ.
  const double* increments(std::size_t wi, double tau);

 private:
  static constexpr std::size_t kEntries = 8;
  template <typename T>
  struct Entry {
    std::vector<double> key;
    std::vector<std::optional<T>> values;
    std::uint64_t used = 0;
  };
  template <typename T>
  std::vector<std::optional<T>>& table(std::vector<Entry<T>>& entries, const std::vector<double>& key);

  struct Increments {
    double tau = 0.0;
    std::vector<double> values;  // two per step of each window, from offsets_
    std::vector<bool> done;      // per window
    std::uint64_t used = 0;
  };

  class ReferenceStore;  // time offset → every window's reference; thread-safe

  const MotionData& d_;
  std::vector<std::size_t> offsets_;  // window → its first value in Increments::values
  std::vector<Increments> increments_;
  std::vector<Entry<Pose2>> predictions_;
  std::shared_ptr<ReferenceStore> references_;
  std::shared_ptr<const std::vector<std::optional<Pose2>>> last_references_;  // what references() returned
  std::uint64_t clock_ = 0;
};

// Negative log-likelihood of the windows `index` (all when empty) under m; windows the shifted
// reference does not cover count with the constant of a perfect fit so that likelihoods stay
// comparable across offsets. `cache` (optional) must belong to d.
double negative_log_likelihood(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index,
                               WindowCache* cache = nullptr);

// Log-density of one residual component r with (squared) scale v: normal (dof = 0) or Student-t.
double component_log_density(double r, double v, double dof);

// Per window of d, the posterior probability under m that it holds a drive stall: the stall
// component's share of the window's likelihood in the mixture negative_log_likelihood sums
// (Bayes' rule with the prior p of stall_odds). None where a stall would not show: m has no
// stalls, the window is heading-only or not covered by the reference, or a stall would move its
// residual by less than kVisibleStallSigmas of its σ along the track (a robot standing still).
inline constexpr double kVisibleStallSigmas = 3.0;
std::vector<std::optional<double>> stall_posteriors(const MotionData& d, const OdometryModel& m);

// Σ|predicted translation| / Σ|logged translation| over all windows: the distance scale a
// path-length ratio measures, with every speed cause and the stalls' expected loss in it.
double mean_distance_scale(const MotionData& d, const OdometryModel& m);

// Relative-pose error of the windows `index`, chained into segments of `chain` consecutive
// windows (relations: each window alone): RMS translation error [m] and RMS heading error [rad].
struct RelativePoseError {
  double translation_rms = 0.0;
  double heading_rms = 0.0;
  std::size_t segments = 0;
};
RelativePoseError relative_pose_error(const MotionData& d, const OdometryModel& m,
                                      const std::vector<std::size_t>& index, std::size_t chain);

}  // namespace locbench::diagnosis
