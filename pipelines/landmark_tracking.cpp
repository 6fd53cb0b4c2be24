#include "pipelines/landmark_tracking.h"

#include <Eigen/LU>  // Matrix3d::determinant
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <variant>

#include "algorithms/filters/bias_augmented_ekf.h"
#include "algorithms/filters/consistency.h"
#include "algorithms/filters/motion_model_ekf.h"
#include "core/chi_square.h"
#include "core/enum_names.h"
#include "core/errors.h"
#include "core/statistics.h"

namespace locbench::experiments::landmarks {
namespace {

using baselines::filters::FixedQEkf, baselines::filters::FixedQEkfOptions, baselines::filters::SageHusaAekf,
    baselines::filters::SageHusaOptions, baselines::filters::VbAkf, baselines::filters::VbAkfOptions;
using filters::BiasAugmentedEkf, filters::CompassEkf, filters::CompassEkfOptions, filters::MotionModelEkf,
    filters::OdometryNoiseForm;

constexpr double kTruthMargin = 2.0;  // [s]

WheelDisplacement wheel_travel(double distance, double turn, double wheelbase) {
  return {distance - 0.5 * wheelbase * turn, distance + 0.5 * wheelbase * turn};
}

// The odometry steps of `d` (logged time) cut at the logged times `cuts` (sorted), each part
// carrying its share of the step's increment (the logged rate is constant within a step).
std::vector<diagnosis::OdometryStep> cut_steps(const std::vector<diagnosis::OdometryStep>& steps,
                                               const std::vector<double>& cuts) {
  std::vector<diagnosis::OdometryStep> out;
  out.reserve(steps.size() + cuts.size());
  std::size_t c = 0;
  for (const auto& s : steps) {
    while (c < cuts.size() && cuts[c] <= s.t0) ++c;
    double t = s.t0;
    const double dt = s.t1 - s.t0;
    while (c < cuts.size() && cuts[c] < s.t1) {
      const double f = dt > 0.0 ? (cuts[c] - t) / dt : 0.0;
      out.push_back({t, cuts[c], s.a * f, s.b * f});
      t = cuts[c];
      ++c;
    }
    const double f = dt > 0.0 ? (s.t1 - t) / dt : 1.0;
    out.push_back({t, s.t1, s.a * f, s.b * f});
  }
  return out;
}

}  // namespace

constexpr EnumNames<Method, 7> kTrackingMethods{{{Method::kFixedQ, "fixed_q"},
                                                 {Method::kAdaptiveThesis, "adaptive_thesis"},
                                                 {Method::kAdaptiveJacobian, "adaptive_jacobian"},
                                                 {Method::kSageHusa, "sage_husa"},
                                                 {Method::kVbAkf, "vb_akf"},
                                                 {Method::kNominalModel, "nominal_model"},
                                                 {Method::kDiagnosedModel, "diagnosed_model"}}};

const char* to_string(Method m) { return enum_name(kTrackingMethods, m); }

TrackingData tracking_data(const Log& log, double from, double to, double wheelbase) {
  TrackingData data;
  data.log = log.name;
  data.from = from;
  data.to = to;
  data.wheelbase = wheelbase;
  if (log.landmark_map.empty()) {
    throw InputError(log.source, 0, "no landmark map: landmark localization needs the surveyed landmarks");
  }
  for (const MapLandmark& l : log.landmark_map) data.map[l.id] = {l.x, l.y};
  for (const LandmarkReading& r : log.landmarks) {
    if (r.t < from || r.t > to) continue;
    if (!data.map.count(r.subject)) {
      ++data.other_robot_observations;
      continue;
    }
    data.observations.push_back({r.t, r.subject, r.range, r.bearing});
  }
  if (data.observations.empty()) {
    throw InputError(log.source, 0, "no observation of a map landmark between the span's ends");
  }
  data.motion = diagnosis::build_motion_data(restrict_log(log, from, to));
  // The truth a little beyond the span, so that a step starting before the span's first truth
  // record (or a model's time offset) still finds its reference.
  data.motion.truth.clear();
  for (const TruePose& p : log.truth) {
    if (p.t >= from - kTruthMargin && p.t <= to + kTruthMargin) data.motion.truth.push_back(p);
  }
  return data;
}

namespace {

// var(mean)/σ² of n observations at spacing g under ρ(Δt) = s·e^(−Δt/τ):
// ((1 − s) + s·S)/n, S = 1 + 2Σ_{k=1}^{n−1}(1 − k/n)a^k = 1 + 2[a/(1 − a) − a(1 − aⁿ)/(n(1 − a)²)].
double block_mean_variance(double n, double g, double share, double tau) {
  const double a = std::exp(-g / tau);
  double pairs = n - 1.0;  // 2Σ as a → 1: every pair fully correlated
  if (1.0 - a > 1e-9) pairs = 2.0 * (a / (1.0 - a) - a * (1.0 - std::pow(a, n)) / (n * (1.0 - a) * (1.0 - a)));
  return ((1.0 - share) + share * (1.0 + std::clamp(pairs, 0.0, n - 1.0))) / n;
}

struct BlockScale {
  double observed = 0.0;                          // mean over blocks of (block mean − overall mean)² / variance
  std::vector<std::pair<double, double>> blocks;  // (count, spacing)
};

}  // namespace

LargeResidualRuns large_residual_runs(const std::vector<double>& z, const std::vector<bool>& adjacent) {
  if (adjacent.size() != z.size()) throw UsageError("large_residual_runs: one adjacency flag per residual");
  LargeResidualRuns out;
  double squares = 0.0, large_squares = 0.0;
  std::size_t negative = 0, runs = 0, run_windows = 0;
  int run_sign = 0;  // the sign of the run going on (0: none)
  for (std::size_t k = 0; k < z.size(); ++k) {
    squares += z[k] * z[k];
    const int sign = z[k] < 0.0 ? -1 : 1;
    if (run_sign != 0 && (!adjacent[k] || sign != run_sign || !(std::abs(z[k]) > kRunResidualSigmas))) run_sign = 0;
    if (std::abs(z[k]) > kLargeResidualSigmas) {
      ++out.windows;
      large_squares += z[k] * z[k];
      negative += sign < 0 ? 1 : 0;
      if (run_sign == 0) {
        ++runs;
        run_sign = sign;
      }
    }
    if (run_sign != 0) ++run_windows;
  }
  if (out.windows == 0) return out;
  out.share_of_squares = large_squares / squares;
  out.negative_fraction = static_cast<double>(negative) / static_cast<double>(out.windows);
  out.mean_run_windows = static_cast<double>(run_windows) / static_cast<double>(runs);
  return out;
}

NoiseCorrelation fit_noise_correlation(const std::vector<double>& t, const std::vector<double>& r) {
  NoiseCorrelation none;
  if (r.size() < 40 || t.size() != r.size()) return none;
  std::vector<double> x = r;
  const double med = quantile(x, 0.5);
  std::vector<double> dev(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) dev[i] = std::abs(x[i] - med);
  const double clip = 4.0 * 1.4826 * quantile(dev, 0.5);
  for (double& v : x) v = std::clamp(v, med - clip, med + clip);
  const double m = mean(x);
  double var = 0.0;
  for (double v : x) var += (v - m) * (v - m);
  var /= static_cast<double>(x.size());
  if (!(var > 0.0)) return none;

  std::vector<BlockScale> scales;
  for (const double length : kCorrelationScales) {
    BlockScale scale;
    double squares = 0.0;
    for (std::size_t i = 0; i < x.size();) {
      const double start = t.front() + length * std::floor((t[i] - t.front()) / length);
      std::size_t j = i;
      double sum = 0.0;
      while (j < x.size() && t[j] < start + length) sum += x[j++];
      const double n = static_cast<double>(j - i);
      if (j - i >= 2) {
        scale.blocks.emplace_back(n, (t[j - 1] - t[i]) / (n - 1.0));
        squares += (sum / n - m) * (sum / n - m) / var;
      }
      i = j;
    }
    if (scale.blocks.size() < kMinBlocksPerScale) continue;
    scale.observed = squares / static_cast<double>(scale.blocks.size());
    if (scale.observed > 0.0) scales.push_back(std::move(scale));
  }
  if (scales.size() < 2) return none;

  // Residuals that share a time stamp (several landmarks in one camera frame) share the common
  // part exactly, so their spread about the frame's mean is the independent part alone: pooled,
  // Σ_frames Σ(x − x̄)² / Σ_frames (n − 1) estimates the white variance and fixes the share.
  double within = 0.0, dof = 0.0;
  for (std::size_t i = 0; i < x.size();) {
    std::size_t j = i;
    double sum = 0.0;
    while (j < x.size() && t[j] == t[i]) sum += x[j++];
    if (j - i >= 2) {
      const double frame_mean = sum / static_cast<double>(j - i);
      for (std::size_t k = i; k < j; ++k) within += (x[k] - frame_mean) * (x[k] - frame_mean);
      dof += static_cast<double>(j - i - 1);
    }
    i = j;
  }
  const bool share_from_frames = dof >= static_cast<double>(kMinFramePairs);
  const double frame_share = share_from_frames ? std::clamp(1.0 - within / dof / var, 0.0, 1.0) : 0.0;

  const auto misfit = [&](double share, double tau) {
    double e = 0.0;
    for (const BlockScale& scale : scales) {
      double model = 0.0;
      for (const auto& [n, g] : scale.blocks) model += block_mean_variance(n, std::max(g, 1e-6), share, tau);
      const double d = std::log(scale.observed) - std::log(model / static_cast<double>(scale.blocks.size()));
      e += d * d;
    }
    return e;
  };
  // A coarse grid, then a finer one around its best: share in [0, 1], τ log-spaced from 0.1 s to the
  // longest block length (a longer time is not seen by the blocks, and would draw a constant offset).
  double best_share = 0.0, best_tau = 1.0, best = misfit(0.0, 1.0);
  const auto search = [&](double s_lo, double s_hi, int s_steps, double ln_lo, double ln_hi, int t_steps) {
    for (int i = 0; i <= s_steps; ++i) {
      const double share = s_lo + (s_hi - s_lo) * i / s_steps;
      for (int j = 0; j <= t_steps; ++j) {
        const double tau = std::exp(ln_lo + (ln_hi - ln_lo) * j / t_steps);
        const double e = misfit(share, tau);
        if (e < best) best = e, best_share = share, best_tau = tau;
      }
    }
  };
  const double ln_lo = std::log(0.1), ln_hi = std::log(std::end(kCorrelationScales)[-1]);
  const double dl = (ln_hi - ln_lo) / 40.0;
  if (share_from_frames) {  // the share is measured: the blocks fit τ alone
    best_share = frame_share;
    best = misfit(best_share, best_tau);
    search(frame_share, frame_share, 1, ln_lo, ln_hi, 40);
    search(frame_share, frame_share, 1, std::max(ln_lo, std::log(best_tau) - dl),
           std::min(ln_hi, std::log(best_tau) + dl), 10);
  } else {
    search(0.0, 1.0, 20, ln_lo, ln_hi, 40);
    const double ds = 0.05;
    search(std::max(0.0, best_share - ds), std::min(1.0, best_share + ds), 10, std::max(ln_lo, std::log(best_tau) - dl),
           std::min(ln_hi, std::log(best_tau) + dl), 10);
  }
  if (!(best_share > 0.0)) return none;
  return {best_share, best_tau};
}

namespace {

// 1.4826·MAD: the σ of normal residuals, robust to their heavy tails.
double robust_sigma(std::vector<double> v) {
  const double med = quantile(v, 0.5);
  for (double& x : v) x = std::abs(x - med);
  return 1.4826 * quantile(v, 0.5);
}

// 1.4826·median |v|: the σ of zero-mean normal values, robust to heavy tails; a shared offset
// (a bias) counts in it, as it should for innovations, whose mean is zero when the filter is right.
double robust_scale_about_zero(std::vector<double> v) {
  for (double& x : v) x = std::abs(x);
  return 1.4826 * quantile(v, 0.5);
}

}  // namespace

double noise_level_spread(const std::vector<double>& t, const std::vector<double>& r) {
  if (t.empty() || t.size() != r.size()) return 0.0;
  std::vector<double> log_sigma, sampling;
  for (std::size_t i = 0; i < r.size();) {
    const double end = t[i] + kLevelBlockS;
    std::vector<double> block;
    for (; i < r.size() && t[i] < end; ++i) block.push_back(r[i]);
    if (block.size() < kMinLevelBlockResiduals) continue;
    const double sigma = robust_sigma(block);
    if (!(sigma > 0.0)) continue;
    log_sigma.push_back(std::log(sigma));
    sampling.push_back(1.35 / static_cast<double>(block.size()));
  }
  if (log_sigma.size() < 3) return 0.0;
  return std::sqrt(std::max(0.0, sample_variance(log_sigma) - mean(sampling)));
}

LandmarkSensorModel measured_sensor_noise(const TrackingData& data, LandmarkSensorModel sensor) {
  std::vector<double> range, bearing, times, range_model_sigma;
  std::vector<int> ids;
  diagnosis::TruthInterpolator truth(data.motion.truth);
  for (const Observation& o : data.observations) {
    const auto p = truth.at(o.t - sensor.time_offset);
    if (!p) continue;
    Eigen::Vector2d m = data.map.at(o.id);
    if (const auto it = sensor.landmark_shift.find(o.id); it != sensor.landmark_shift.end()) m += it->second;
    const double dx = m.x() - p->x, dy = m.y() - p->y;
    const double rho = std::hypot(dx, dy), phi = wrap_angle(std::atan2(dy, dx) - p->theta);
    times.push_back(o.t);
    ids.push_back(o.id);
    range.push_back(o.range - (sensor.range_scale_at(phi) * rho + sensor.range_bias));
    range_model_sigma.push_back(std::max(1e-9, std::hypot(sensor.range_sigma, sensor.range_noise_slope * rho)));
    bearing.push_back(angle_diff(o.bearing, phi + sensor.bearing_bias));
  }
  if (range.size() < 20) throw InputError(data.log, 0, "fewer than 20 landmark observations with ground truth");
  sensor.range_sigma = robust_sigma(range);
  sensor.bearing_sigma = robust_sigma(bearing);
  // Per-landmark medians: their spread, and the residuals without them for the time correlation.
  std::map<int, std::vector<std::size_t>> by_landmark;
  for (std::size_t i = 0; i < ids.size(); ++i) by_landmark[ids[i]].push_back(i);
  std::vector<double> range_medians, bearing_medians;
  std::vector<double> range_within = range, bearing_within = bearing;
  for (const auto& [id, index] : by_landmark) {
    std::vector<double> r, b;
    for (std::size_t i : index) r.push_back(range[i]), b.push_back(bearing[i]);
    const double mr = quantile(r, 0.5), mb = quantile(b, 0.5);
    for (std::size_t i : index) range_within[i] -= mr, bearing_within[i] -= mb;
    if (index.size() >= 10) range_medians.push_back(mr), bearing_medians.push_back(mb);
  }
  sensor.structure = {};
  if (range_medians.size() >= 3) {
    sensor.structure.range_landmark_sigma = robust_sigma(range_medians);
    sensor.structure.bearing_landmark_sigma = robust_sigma(bearing_medians);
  }
  // The level's spread on residuals in units of the given sensor's σ(ρ): a range-dependent noise
  // the sensor already models is not counted again as a level that varies.
  std::vector<double> range_standardized(range_within.size());
  for (std::size_t i = 0; i < range_within.size(); ++i) range_standardized[i] = range_within[i] / range_model_sigma[i];
  sensor.structure.range_level_sigma = noise_level_spread(times, range_standardized);
  sensor.structure.bearing_level_sigma = noise_level_spread(times, bearing_within);
  sensor.structure.range_correlation = fit_noise_correlation(times, range_within);
  sensor.structure.bearing_correlation = fit_noise_correlation(times, bearing_within);
  // Outliers: beyond kOutlierSigmas robust σ in either channel, against the share the noise model
  // gives there (its robust σ is 1.4826·F⁻¹(0.75) in its own units; the channels independent).
  std::vector<double> range_units(range.size());
  for (std::size_t i = 0; i < range.size(); ++i) range_units[i] = range[i] / range_model_sigma[i];
  const double range_scale = robust_sigma(range_units), bearing_scale = robust_sigma(bearing);
  for (std::size_t i = 0; i < range.size(); ++i) {
    if (std::abs(range_units[i]) > kOutlierSigmas * range_scale ||
        std::abs(bearing[i]) > kOutlierSigmas * bearing_scale)
      sensor.structure.outliers.emplace_back(range_units[i], bearing[i]);
  }
  const double beyond = kOutlierSigmas * 1.4826 * student_t_quantile(0.75, sensor.dof);
  const double channel = student_t_two_sided_tail(beyond, sensor.dof);
  const double expected = 1.0 - (1.0 - channel) * (1.0 - channel);
  const double observed = static_cast<double>(sensor.structure.outliers.size()) / static_cast<double>(range.size());
  sensor.structure.outlier_rate = std::max(0.0, observed - expected);
  if (!(sensor.structure.outlier_rate > 0.0)) sensor.structure.outliers.clear();
  return sensor;
}

std::vector<MotionStep> model_motion(const TrackingData& data, const diagnosis::OdometryModel& model,
                                     double noise_window_s, const std::vector<double>& cuts) {
  diagnosis::MotionData d;
  d.odometry = data.motion.odometry;
  d.nominal = data.motion.nominal;
  std::vector<double> logged_cuts;
  logged_cuts.reserve(cuts.size());
  for (double t : cuts) logged_cuts.push_back(t + model.time_offset);  // logged = true + offset
  std::sort(logged_cuts.begin(), logged_cuts.end());
  d.steps = cut_steps(data.motion.steps, logged_cuts);

  diagnosis::OdometryModel mean_model = model;  // the stalls' loss is applied below, per step
  mean_model.stall_rate = 0.0;
  mean_model.stall_duration = 0.0;
  const double stall_time = model.stall_rate * model.stall_duration;
  const double phi = stall_time > 0.0 ? stall_time / (1.0 + stall_time) : 0.0;
  const double b = d.nominal.wheelbase > 0.0 ? d.nominal.wheelbase : 0.5;  // as the diagnosis's windows
  const double tail = model.dof > 2.0 ? model.dof / (model.dof - 2.0) : 1.0;
  const Vector3 floor_per_s =
      Vector3(model.sigma_x * model.sigma_x, model.sigma_y * model.sigma_y, model.sigma_theta * model.sigma_theta) *
      (tail / noise_window_s);

  std::vector<MotionStep> out;
  out.reserve(d.steps.size());
  diagnosis::MotionWindow w;
  for (std::size_t i = 0; i < d.steps.size(); ++i) {
    w.first = i;
    w.last = i + 1;
    w.t0 = d.steps[i].t0;
    w.t1 = d.steps[i].t1;
    const Pose2 p = diagnosis::predict_window(d, w, mean_model);  // eq. 1.3 on the model's rates
    MotionStep s;
    s.t0 = w.t0 - model.time_offset;
    s.t1 = w.t1 - model.time_offset;
    const double chord = std::hypot(p.x, p.y);
    const double full = p.x < 0.0 ? -chord : chord;
    s.distance = (1.0 - phi) * full;
    if (phi > 0.0) s.stall_distance = full;
    s.turn = p.theta;
    const double dt = s.t1 - s.t0;
    const double travel = 2.0 * std::abs(full) + std::abs(p.theta) * b;  // W of the diagnosis's windows
    Vector3 v = floor_per_s * dt;
    v(0) += model.k2 * travel / 4.0;  // eq. 4.36 with k²
    v(1) += model.k2 * travel / 4.0;
    v(2) += model.k2 * travel / (b * b);  // eq. 4.37
    s.body_covariance = v.asDiagonal();
    out.push_back(s);
  }
  return out;
}

namespace {

// Adjacent window means of a Gauss–Markov process with x = window/τ: their correlation.
double adjacent_mean_correlation(double x) {
  const double e = std::exp(-x);
  return (1.0 - e) * (1.0 - e) / (2.0 * (x - 1.0 + e));
}

}  // namespace

filters::GaussMarkovBias stall_loss_process(const diagnosis::OdometryModel& model, double window_s,
                                            double persistence) {
  const diagnosis::StallOdds odds = diagnosis::window_stall_odds(model, window_s);
  if (!(odds.p > 0.0) || !(odds.fraction > 0.0)) return {};
  double x = window_s * (model.stall_rate + 1.0 / model.stall_duration);
  if (persistence > odds.p && odds.p < 1.0) {
    const double rho = std::min((persistence - odds.p) / (1.0 - odds.p), 0.999);
    double lo = 1e-6, hi = 1e3;  // the correlation falls from 1 to 0 as x grows
    for (int i = 0; i < 100; ++i) {
      const double mid = std::sqrt(lo * hi);
      (adjacent_mean_correlation(mid) > rho ? lo : hi) = mid;
    }
    x = std::sqrt(lo * hi);
  }
  const double g = 2.0 * (x - 1.0 + std::exp(-x)) / (x * x);
  const double window_variance = odds.p * (1.0 - odds.p) * odds.fraction * odds.fraction;
  return {std::sqrt(window_variance / g), window_s / x};
}

double TrackResult::position_rmse() const { return position_error.empty() ? 0.0 : rms(position_error); }
double TrackResult::log_score() const {
  if (diverged || nees.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t i = 0; i < nees.size(); ++i) sum += 0.5 * (nees[i] + log_det_covariance[i]);
  const double score = sum / static_cast<double>(nees.size());
  return std::isfinite(score) ? score : std::numeric_limits<double>::infinity();
}
double TrackResult::heading_rmse() const { return heading_error.empty() ? 0.0 : rms(heading_error); }
double TrackResult::gated_fraction() const {
  return observations > 0 ? static_cast<double>(gated) / static_cast<double>(observations) : 0.0;
}

namespace {

// The odometry's turn rate [rad/s] over the step that holds true time t (0 outside the steps).
double turn_rate_at(const std::vector<MotionStep>& steps, double t) {
  const auto it =
      std::upper_bound(steps.begin(), steps.end(), t, [](double v, const MotionStep& s) { return v < s.t1; });
  if (it == steps.end() || t < it->t0 || !(it->t1 > it->t0)) return 0.0;
  return it->turn / (it->t1 - it->t0);
}

using AnyFilter = std::variant<FixedQEkf, CompassEkf, SageHusaAekf, VbAkf, MotionModelEkf, BiasAugmentedEkf>;

// Does the method estimate R itself (its knob is a forgetting factor, not an R scale)?
bool estimates_r(Method m) { return m == Method::kSageHusa || m == Method::kVbAkf; }

// The share of a channel's noise that is correlated in time, as a Gauss–Markov bias of the filter's
// state: variance share·σ² (σ the channel's white-noise σ, in the corrected measurement's units).
filters::GaussMarkovBias correlated_part(const NoiseCorrelation& c, double sigma, double r_scale) {
  return {std::sqrt(r_scale * c.share) * sigma, c.time_s > 0.0 ? c.time_s : 1.0};
}

filters::MotionNoiseCorrelation motion_correlation(const MotionNoiseStructure& m, double window_s) {
  filters::MotionNoiseCorrelation c;
  const NoiseCorrelation* parts[] = {&m.x, &m.y, &m.theta};
  for (int j = 0; j < 3; ++j) {
    c.share(j) = std::clamp(parts[j]->share, 0.0, 0.99);  // a white remainder: the filter needs s < 1
    c.time_s(j) = parts[j]->time_s > 0.0 ? parts[j]->time_s : 1.0;
  }
  c.window_s = window_s;
  return c;
}

AnyFilter make_filter(const MethodSetup& s, double wheelbase, const Pose2& start) {
  const Vector3 p0 = s.initial_sigma.cwiseProduct(s.initial_sigma);
  switch (s.method) {
    case Method::kFixedQ: {
      FixedQEkfOptions o;
      o.process_noise = s.fixed_q_per_s * s.process_scale;
      o.initial_covariance = p0;
      return FixedQEkf(o, wheelbase, start);
    }
    case Method::kAdaptiveThesis:
    case Method::kAdaptiveJacobian: {
      CompassEkfOptions o;
      o.noise = s.adaptive;
      o.noise.form = s.method == Method::kAdaptiveThesis ? OdometryNoiseForm::kThesis : OdometryNoiseForm::kJacobian;
      o.process_noise_scale = s.process_scale;
      o.initial_covariance = p0;
      return CompassEkf(o, wheelbase, start);
    }
    case Method::kSageHusa: {
      SageHusaOptions o;
      o.initial_process_noise = s.fixed_q_per_s * s.process_scale;
      o.forgetting = s.knob;
      o.initial_covariance = p0;
      o.min_statistics_interval = 0.1;  // [s]: the camera's frames come ~0.2–0.3 s apart
      return SageHusaAekf(o, wheelbase, start);
    }
    case Method::kVbAkf: {
      VbAkfOptions o;
      o.process_noise = s.fixed_q_per_s * s.process_scale;
      o.forgetting = s.knob;
      o.initial_covariance = p0;
      return VbAkf(o, wheelbase, start);
    }
    case Method::kNominalModel:
    case Method::kDiagnosedModel:
      if (s.sensor.correlated() || s.motion_structure.correlated() || s.stall.sigma > 0.0) {
        const NoiseStructure& st = s.sensor.structure;
        filters::MotionNoiseCorrelation motion = motion_correlation(s.motion_structure, s.noise_window_s);
        motion.stall = {std::sqrt(s.process_scale) * s.stall.sigma, s.stall.time_s};
        return BiasAugmentedEkf(
            wheelbase, start, Matrix3(p0.asDiagonal()),
            {correlated_part(st.range_correlation, s.sensor.range_sigma / s.sensor.range_scale, s.knob),
             correlated_part(st.bearing_correlation, s.sensor.bearing_sigma, s.knob)},
            motion);
      }
      return MotionModelEkf(wheelbase, start, Matrix3(p0.asDiagonal()));
  }
  throw std::logic_error("make_filter: unknown method");
}

struct TimedObservation {
  double t;  // true time [s]
  LandmarkRangeBearing z;
};

// Observations in true time, with the sensor model's corrections (Table 7.2's z, inverted), in
// time order. `carries_correlated_noise`: the filter carries the correlated part of the noise as states, so
// the measurement variance holds the white part only.
std::vector<TimedObservation> timed_observations(const TrackingData& data, const MethodSetup& setup,
                                                 const std::vector<MotionStep>& steps, bool carries_correlated_noise) {
  const LandmarkSensorModel& sm = setup.sensor;
  const double r_scale = estimates_r(setup.method) ? 1.0 : setup.knob;
  std::vector<TimedObservation> obs;
  obs.reserve(data.observations.size());
  for (const Observation& o : data.observations) {
    Eigen::Vector2d m = data.map.at(o.id);
    if (const auto it = sm.landmark_shift.find(o.id); it != sm.landmark_shift.end()) m += it->second;
    LandmarkRangeBearing z;
    z.bearing = o.bearing - sm.bearing_bias;
    // The scale at the measured bearing (its noise moves the scale by ~2k·φ·σ_φ, negligible).
    const double scale = sm.range_scale_at(wrap_angle(z.bearing));
    z.range = (o.range - sm.range_bias) / scale;
    z.landmark_x = m.x();
    z.landmark_y = m.y();
    // The white part of the noise (all of it unless the filter carries the correlated part as biases).
    const double range_white = carries_correlated_noise ? 1.0 - sm.structure.range_correlation.share : 1.0;
    const double bearing_white = carries_correlated_noise ? 1.0 - sm.structure.bearing_correlation.share : 1.0;
    const double sr = sm.range_noise_slope * z.range;
    z.range_variance = r_scale * (range_white * sm.range_sigma * sm.range_sigma + sr * sr) / (scale * scale);
    const double sb = sm.bearing_noise_turn_slope * turn_rate_at(steps, o.t - sm.time_offset);
    z.bearing_variance = r_scale * (bearing_white * sm.bearing_sigma * sm.bearing_sigma + sb * sb);
    obs.push_back({o.t - sm.time_offset, z});
  }
  std::stable_sort(obs.begin(), obs.end(),
                   [](const TimedObservation& a, const TimedObservation& b) { return a.t < b.t; });
  return obs;
}

// The standardized range and bearing innovations of the motion-model EKF, and with `tracks` the
// measurement variances scaled by their level over the last kLevelBlockS seconds against the
// reference level.
class InnovationLevel {
 public:
  InnovationLevel(bool tracks, const Eigen::Vector2d& reference) : tracks_(tracks), reference_(reference) {}

  // `innovation`: z's innovation and its covariance at the filter's state, before any scaling.
  void scale_and_record(LandmarkRangeBearing& z, const MeasurementUpdate& innovation, double now) {
    const MeasurementVector& nu = innovation.innovation;
    const MeasurementMatrix& s = innovation.innovation_covariance;
    if (tracks_) {
      while (window_start_ < t_.size() && t_[window_start_] < now - kLevelBlockS) ++window_start_;
      if (t_.size() - window_start_ >= kMinLevelBlockResiduals) {
        for (int c = 0; c < 2; ++c) {
          const double sigma = robust_scale_about_zero(std::vector<double>(
              innovation_[c].begin() + static_cast<std::ptrdiff_t>(window_start_), innovation_[c].end()));
          const double ratio = sigma / reference_(c);
          const double level = std::clamp(ratio * ratio, 1.0 / kMaxLevelRatio, kMaxLevelRatio);
          (c == 0 ? z.range_variance : z.bearing_variance) *= level;
        }
      }
    }
    t_.push_back(now);
    for (int c = 0; c < 2; ++c) innovation_[c].push_back(nu(c) / std::sqrt(s(c, c)));
  }

  std::size_t count() const { return t_.size(); }
  const std::vector<double>& innovations(int c) const { return innovation_[static_cast<std::size_t>(c)]; }

 private:
  bool tracks_;
  Eigen::Vector2d reference_;
  std::vector<double> t_;
  std::array<std::vector<double>, 2> innovation_;
  std::size_t window_start_ = 0;
};

// One reweighting step of the Student-t likelihood with `dof` degrees of freedom.
double student_t_weight(AnyFilter& filter, const LandmarkRangeBearing& z, double dof) {
  const double nis = std::visit(
      [&](auto& f) {
        if constexpr (std::is_same_v<std::decay_t<decltype(f)>, BiasAugmentedEkf>) {
          return f.nis(z);
        } else {
          const LinearizedMeasurement lin = linearize(z, f.mean());
          return measurement_innovation(lin, f.covariance(), lin.R).nis;
        }
      },
      filter);
  return std::max(1.0, (dof + nis) / (dof + 2.0));
}

void predict_step(AnyFilter& filter, const MotionStep& s, const WheelDisplacement& u, double process_scale) {
  const double dt = s.t1 - s.t0;
  std::visit(
      [&](auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<F, MotionModelEkf>) {
          f.predict(u, process_scale * s.body_covariance);
        } else if constexpr (std::is_same_v<F, BiasAugmentedEkf>) {
          f.predict(u, process_scale * s.body_covariance, dt, s.stall_distance);
        } else if constexpr (std::is_same_v<F, CompassEkf>) {
          f.predict(u);
        } else {
          f.predict(u, dt);  // Q per second
        }
      },
      filter);
}

// The observations fed to the filter in time order, gated; after `starve_after` gated ones in a
// row the next is taken ungated (a recovery).
class ObservationFeed {
 public:
  ObservationFeed(std::vector<TimedObservation> obs, const MethodSetup& setup, const GatePolicy& gate)
      : obs_(std::move(obs)),
        setup_(setup),
        gate_(gate),
        threshold_(chi_square_quantile(ChiSquareDof(2.0), gate.gate_probability)),
        tracks_level_(setup.level_reference.minCoeff() > 0.0 &&
                      (setup.method == Method::kNominalModel || setup.method == Method::kDiagnosedModel)),
        measures_level_(tracks_level_ || setup.measure_innovation_level),
        level_(tracks_level_, setup.level_reference) {}

  // Every observation up to time t.
  void until(double t, AnyFilter& filter, TrackResult& out) {
    for (; next_ < obs_.size() && obs_[next_].t <= t; ++next_) {
      ++out.observations;
      const bool recover = starving_ >= gate_.starve_after;
      LandmarkRangeBearing z = obs_[next_].z;
      if (measures_level_) {
        if (const auto* ekf = std::get_if<MotionModelEkf>(&filter)) {
          const LinearizedMeasurement lin = linearize(z, ekf->mean());
          level_.scale_and_record(z, measurement_innovation(lin, ekf->covariance(), lin.R), obs_[next_].t);
        } else if (const auto* augmented = std::get_if<BiasAugmentedEkf>(&filter)) {
          level_.scale_and_record(z, augmented->innovation(z), obs_[next_].t);
        }
      }
      if (setup_.sensor.dof > 0.0) {
        const double w = student_t_weight(filter, z, setup_.sensor.dof);
        z.range_variance *= w;
        z.bearing_variance *= w;
      }
      const MeasurementUpdate u =
          std::visit([&](auto& f) { return f.update(z, recover ? kNoGate : threshold_); }, filter);
      if (u.gated) {
        ++out.gated;
        ++starving_;
      } else {
        ++out.used;
        if (recover) ++out.recoveries;
        starving_ = 0;
      }
    }
  }

  const InnovationLevel& level() const { return level_; }

 private:
  std::vector<TimedObservation> obs_;
  const MethodSetup& setup_;
  const GatePolicy& gate_;
  double threshold_;
  bool tracks_level_, measures_level_;
  InnovationLevel level_;
  std::size_t next_ = 0;
  int starving_ = 0;
};

}  // namespace

TrackResult track(const TrackingData& data, const MethodSetup& setup, const GatePolicy& gate) {
  if (!setup.motion || setup.motion->empty()) throw UsageError("track: no motion steps");
  const std::vector<MotionStep>& steps = *setup.motion;
  if (!(setup.stall.sigma > 0.0) &&
      std::any_of(steps.begin(), steps.end(), [](const MotionStep& s) { return s.stall_distance != 0.0; }))
    throw UsageError("track: motion steps with stalls need the stall loss process (MethodSetup::stall)");
  diagnosis::TruthInterpolator truth(data.motion.truth);
  const auto start = diagnosis::interpolate_truth(data.motion.truth, steps.front().t0);
  if (!start) throw InputError(data.log, 0, "the ground truth does not cover the span's start");
  AnyFilter filter = make_filter(setup, data.wheelbase, *start);
  const bool carries_correlated_noise = std::holds_alternative<BiasAugmentedEkf>(filter);
  ObservationFeed feed(timed_observations(data, setup, steps, carries_correlated_noise), setup, gate);

  TrackResult out;
  feed.until(steps.front().t0, filter, out);
  std::size_t far = 0;
  for (const MotionStep& s : steps) {
    predict_step(filter, s, wheel_travel(s.distance, s.turn, data.wheelbase), setup.process_scale);
    feed.until(s.t1, filter, out);
    const Vector3 x = std::visit([](auto& f) { return f.mean(); }, filter);
    const Matrix3 p = std::visit([](auto& f) { return f.covariance(); }, filter);
    if (!x.allFinite() || !p.allFinite()) {
      out.finite = false;
      break;
    }
    const auto ref = truth.at(s.t1);
    if (!ref) continue;
    out.t.push_back(s.t1);
    const double e = std::hypot(ref->x - x(0), ref->y - x(1));
    out.position_error.push_back(e);
    out.heading_error.push_back(angle_diff(ref->theta, x(2)));
    out.nees.push_back(filters::pose_nees(*ref, x, p));
    out.log_det_covariance.push_back(std::log(p.determinant()));
    if (e > gate.divergence_error_m) ++far;
  }
  if (feed.level().count() >= 20)
    for (int c = 0; c < 2; ++c) out.innovation_sigma(c) = robust_scale_about_zero(feed.level().innovations(c));
  out.diverged = !out.finite || out.position_error.empty() ||
                 static_cast<double>(far) >= 0.05 * static_cast<double>(out.position_error.size());
  return out;
}

}  // namespace locbench::experiments::landmarks
