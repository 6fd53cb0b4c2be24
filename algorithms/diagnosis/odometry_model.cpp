#include "algorithms/diagnosis/odometry_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include "core/angle.h"
#include "core/units.h"

namespace locbench::diagnosis {
namespace {

// Exact arc integration of one step (eq. 1.3 with the chord of the arc).
Pose2 advance(const Pose2& p, double dd, double dth) {
  const double half = 0.5 * dth;
  const double chord = std::abs(half) < 1e-6 ? dd : dd * std::sin(half) / half;
  return {p.x + chord * std::cos(p.theta + half), p.y + chord * std::sin(p.theta + half), p.theta + dth};
}

double wheelbase_or_default(const MotionData& d) { return d.nominal.wheelbase > 0.0 ? d.nominal.wheelbase : 0.5; }

// First-order drive response over one step of constant logged rate `v` (v̇ = 0 within the step),
// `decay` = e^(−Δt/τ): returns the true increment and advances the state u (the true rate at the
// step's end).
double respond(double& u, double v, double dt, double tau, double decay) {
  const double increment = v * dt + (u - v) * tau * (1.0 - decay);
  u = v + (u - v) * decay;
  return increment;
}

bool has_stalls(const MotionData& d, const OdometryModel& m) {
  return d.odometry == OdometryKind::kPose && m.stall_rate > 0.0 && m.stall_duration > 0.0;
}

StallOdds stall_odds(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  return has_stalls(d, m) ? window_stall_odds(m, w.t1 - w.t0) : StallOdds{};
}

}  // namespace

StallOdds window_stall_odds(const OdometryModel& m, double span) {
  if (!(m.stall_rate > 0.0 && m.stall_duration > 0.0 && span > 0.0)) return {};
  return {-std::expm1(-m.stall_rate * span), std::min(m.stall_duration / span, 1.0)};
}

WheelStepMeans mean_wheel_steps(const MotionData& d, const MotionWindow& w) {
  WheelStepMeans m;
  for (std::size_t i = w.first; i < w.last; ++i) {
    m.left += d.steps[i].a * d.nominal.meters_per_tick_left;
    m.right += d.steps[i].b * d.nominal.meters_per_tick_right;
  }
  const double ns = static_cast<double>(w.last - w.first);
  m.left /= ns;
  m.right /= ns;
  return m;
}

double expected_stall_loss(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  const StallOdds s = stall_odds(d, w, m);
  return s.p * s.fraction;
}

namespace {

bool contiguous(const MotionData& d, std::size_t i) { return d.steps[i - 1].t1 == d.steps[i].t0; }

double midpoint(const OdometryStep& s) { return 0.5 * (s.t0 + s.t1); }

// The logged rates at time t inside step k, interpolated linearly between the midpoints of k and
// its contiguous neighbour on t's side (k's own rates where there is none).
void interpolated_rates(const MotionData& d, std::size_t k, double t, DriveRunIn& r) {
  const StepRates here = step_rates(d.steps[k]);
  r.v = here.v;
  r.rate = here.rate;
  r.v_slope = r.rate_slope = 0.0;
  const double mid = midpoint(d.steps[k]);
  std::size_t other = k;
  if (t < mid && k > 0 && contiguous(d, k)) other = k - 1;
  if (t >= mid && k + 1 < d.steps.size() && contiguous(d, k + 1)) other = k + 1;
  const double span = midpoint(d.steps[other]) - mid;
  if (other == k || span == 0.0) return;
  const StepRates there = step_rates(d.steps[other]);
  r.v_slope = (there.v - here.v) / span;
  r.rate_slope = (there.rate - here.rate) / span;
  r.v += r.v_slope * (t - mid);
  r.rate += r.rate_slope * (t - mid);
}

}  // namespace

DriveRunIn drive_run_in(const MotionData& d, const MotionWindow& w, double tau) {
  DriveRunIn r;
  r.step = w.first;
  if (w.first >= d.steps.size()) return r;
  r.t = d.steps[w.first].t0;
  if (!(tau > 0.0)) return r;
  r.t -= 4.0 * tau;
  while (r.step > 0 && d.steps[r.step].t0 > r.t && contiguous(d, r.step)) --r.step;
  if (d.steps[r.step].t0 > r.t) {
    r.t = d.steps[r.step].t0;
    r.clamped = true;
  }
  interpolated_rates(d, r.step, r.t, r);
  return r;
}

void drive_increments(const MotionData& d, const MotionWindow& w, double tau, double* out) {
  const DriveRunIn r = drive_run_in(d, w, tau);
  double u = r.v, omega = r.rate;
  for (std::size_t i = r.step; i < w.last; ++i) {
    const auto& s = d.steps[i];
    auto [dt, v, rate] = step_rates(s);
    if (i == r.step && i < w.first) dt = s.t1 - r.t;  // the part of the run-in's first step after t_s
    double dd = s.a, dth = s.b;
    if (tau > 0.0 && dt > 0.0) {
      const double decay = std::exp(-dt / tau);
      dd = respond(u, v, dt, tau, decay);
      dth = respond(omega, rate, dt, tau, decay);
    }
    if (i < w.first) continue;
    out[2 * (i - w.first)] = dd;
    out[2 * (i - w.first) + 1] = dth;
  }
}

Pose2 predict_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m, const double* increments) {
  Pose2 p;
  if (d.odometry == OdometryKind::kEncoder) {
    const double cl = d.nominal.meters_per_tick_left * m.E_o * 2.0 / (1.0 + m.E_d);
    const double cr = d.nominal.meters_per_tick_right * m.E_o * 2.0 * m.E_d / (1.0 + m.E_d);
    const double b = d.nominal.wheelbase * m.E_b;
    for (std::size_t i = w.first; i < w.last; ++i) {
      const double ul = cl * d.steps[i].a, ur = cr * d.steps[i].b;
      p = advance(p, 0.5 * (ul + ur), (ur - ul) / b);
    }
    return p;
  }
  const double kept = 1.0 - expected_stall_loss(d, w, m);
  for (std::size_t i = w.first; i < w.last; ++i) {
    const auto [dt, v, rate] = step_rates(d.steps[i]);
    const double* inc = increments + 2 * (i - w.first);
    const double scale = (m.velocity_scale + m.speed_slope * std::abs(v)) * kept;
    p = advance(p, scale * inc[0], m.turn_rate_scale * inc[1] + m.turn_rate_bias * dt);
  }
  return p;
}

Pose2 predict_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  if (d.odometry == OdometryKind::kEncoder) return predict_window(d, w, m, nullptr);
  std::vector<double> increments(2 * (w.last - w.first));
  drive_increments(d, w, m.drive_tau, increments.data());
  return predict_window(d, w, m, increments.data());
}

std::optional<Pose2> reference_window(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  switch (d.reference) {
    case ReferenceKind::kRelations: return w.reference;
    case ReferenceKind::kTruePose: {
      const auto a = interpolate_truth(d.truth, w.t0 - m.time_offset);
      const auto b = interpolate_truth(d.truth, w.t1 - m.time_offset);
      if (!a || !b) return std::nullopt;
      return between(*a, *b);
    }
    case ReferenceKind::kCompass: {
      const auto a = interpolate_compass(d.compass, w.t0 - m.time_offset);
      const auto b = interpolate_compass(d.compass, w.t1 - m.time_offset);
      if (!a || !b) return std::nullopt;
      return Pose2(0.0, 0.0, angle_diff(*b, *a));
    }
  }
  return std::nullopt;
}

Eigen::Vector3d window_variance(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  const double b = wheelbase_or_default(d);
  const double growth = m.k2 * w.wheel_travel;
  return {m.sigma_x * m.sigma_x + growth / 4.0, m.sigma_y * m.sigma_y + growth / 4.0,
          m.sigma_theta * m.sigma_theta + growth / (b * b)};
}

namespace {

WindowResidual residual_of(const MotionData& d, const MotionWindow& w, const OdometryModel& m,
                           const std::optional<Pose2>& ref, const Pose2& pred) {
  WindowResidual out;
  if (!ref) return out;
  out.variance = window_variance(d, w, m);
  out.prediction = pred;
  out.valid = true;
  out.heading_only = d.reference == ReferenceKind::kCompass;
  out.r = {ref->x - pred.x, ref->y - pred.y, angle_diff(ref->theta, pred.theta)};
  if (out.heading_only) out.r.head<2>().setZero();
  return out;
}

std::vector<double> mean_key(const OdometryModel& m) {
  // Stalls move the prediction only when both their parameters are positive (stall_odds): the
  // likelihood's mean model has rate 0, and then any duration predicts the same.
  const bool stalls = m.stall_rate > 0.0 && m.stall_duration > 0.0;
  return {m.E_d,
          m.E_b,
          m.E_o,
          m.velocity_scale,
          m.turn_rate_scale,
          m.turn_rate_bias,
          m.speed_slope,
          m.drive_tau,
          stalls ? m.stall_rate : 0.0,
          stalls ? m.stall_duration : 0.0};
}

}  // namespace

WindowResidual window_residual(const MotionData& d, const MotionWindow& w, const OdometryModel& m) {
  const auto ref = reference_window(d, w, m);
  return residual_of(d, w, m, ref, ref ? predict_window(d, w, m) : Pose2());
}

namespace {
constexpr std::size_t kReferenceEntries = 256;  // reference windows at this many time offsets
// Predictions for this many mean models: a Newton step by central differences (where exact
// derivatives are not given, ml_fit.cpp) asks for each mean parameter ± h alone and in pairs.
constexpr std::size_t kPredictionEntries = 32;

// The entry of `entries` that `matches` (the last such); else a slot for a new one, `is_new` set:
// appended while fewer than `limit` are held, else the least recently used one.
template <class Entry, class Matches>
Entry& entry_or_slot(std::vector<Entry>& entries, std::size_t limit, Matches matches, bool& is_new) {
  Entry* e = nullptr;
  for (auto& x : entries) {
    if (matches(x)) e = &x;
  }
  is_new = e == nullptr;
  if (!is_new) return *e;
  if (entries.size() < limit) return entries.emplace_back();
  return *std::min_element(entries.begin(), entries.end(),
                           [](const auto& a, const auto& b) { return a.used < b.used; });
}
}  // namespace

// The references of every window at each time offset asked for, kept for the last
// kReferenceEntries offsets asked for. Shared by a cache's copies, which may run side by side.
class WindowCache::ReferenceStore {
 public:
  using References = std::vector<std::optional<Pose2>>;
  std::shared_ptr<const References> at(const MotionData& d, double offset) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (const auto it = entries_.find(offset); it != entries_.end()) {
        it->second.used = ++clock_;
        return it->second.values;
      }
    }
    OdometryModel m;
    m.time_offset = offset;
    auto values = std::make_shared<References>();
    values->reserve(d.windows.size());
    for (const MotionWindow& w : d.windows) values->push_back(reference_window(d, w, m));
    const std::lock_guard<std::mutex> lock(mutex_);
    auto [it, inserted] = entries_.try_emplace(offset, Entry{std::move(values), 0});
    it->second.used = ++clock_;
    if (inserted && entries_.size() > kReferenceEntries) {
      entries_.erase(std::min_element(entries_.begin(), entries_.end(),
                                      [](const auto& a, const auto& b) { return a.second.used < b.second.used; }));
    }
    return it->second.values;
  }

 private:
  struct Entry {
    std::shared_ptr<const References> values;
    std::uint64_t used = 0;
  };
  std::mutex mutex_;
  std::map<double, Entry> entries_;
  std::uint64_t clock_ = 0;
};

WindowCache::WindowCache(const MotionData& d) : d_(d), references_(std::make_shared<ReferenceStore>()) {
  predictions_.reserve(kPredictionEntries);
  increments_.reserve(kEntries);
  offsets_.reserve(d.windows.size() + 1);
  std::size_t at = 0;
  for (const auto& w : d.windows) {
    offsets_.push_back(at);
    at += 2 * (w.last - w.first);
  }
  offsets_.push_back(at);
}

const double* WindowCache::increments(std::size_t wi, double tau) {
  ++clock_;
  bool is_new = false;
  Increments& e = entry_or_slot(
      increments_, kEntries, [&](const Increments& x) { return x.tau == tau; }, is_new);
  if (is_new) {
    e.tau = tau;
    e.values.resize(offsets_.back());
    e.done.assign(d_.windows.size(), false);
  }
  e.used = clock_;
  double* out = e.values.data() + offsets_[wi];
  if (!e.done[wi]) {
    drive_increments(d_, d_.windows[wi], tau, out);
    e.done[wi] = true;
  }
  return out;
}

template <typename T>
std::vector<std::optional<T>>& WindowCache::table(std::vector<Entry<T>>& entries, const std::vector<double>& key) {
  ++clock_;
  const std::size_t limit = kPredictionEntries;
  bool is_new = false;
  Entry<T>& e = entry_or_slot(
      entries, limit, [&](const Entry<T>& x) { return x.key == key; }, is_new);
  if (is_new) {
    e.key = key;
    e.values.assign(d_.windows.size(), std::nullopt);
  }
  e.used = clock_;
  return e.values;
}

std::vector<std::optional<Pose2>>& WindowCache::predictions(const OdometryModel& m) {
  return table(predictions_, mean_key(m));
}

const std::vector<std::optional<Pose2>>& WindowCache::references(const OdometryModel& m) {
  last_references_ = references_->at(d_, m.time_offset);
  return *last_references_;
}

namespace {

// The Student-t density's constant lgamma((ν+1)/2) − lgamma(ν/2) − ½·log(νπ), once per model.
struct Density {
  explicit Density(double nu)
      : dof(nu),
        constant(nu > 0.0 ? std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) - 0.5 * std::log(nu * kPi) : 0.0) {}
  double operator()(double r, double v) const {
    if (!(dof > 0.0)) return -0.5 * (r * r / v + log_of(2.0 * kPi * v));
    return constant - 0.5 * log_of(v) - 0.5 * (dof + 1.0) * std::log1p(r * r / (dof * v));
  }
  // std::log of the last three arguments remembered: without noise growth the three components'
  // variances are the same in every window.
  double log_of(double x) const {
    for (int i = 0; i < 3; ++i) {
      if (keys[i] == x) return logs[i];
    }
    const double l = std::log(x);
    keys[next] = x;
    logs[next] = l;
    next = (next + 1) % 3;
    return l;
  }
  double dof, constant;
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // equal to nothing
  mutable double keys[3] = {kNone, kNone, kNone}, logs[3] = {0.0, 0.0, 0.0};
  mutable int next = 0;
};

double log_density(const Eigen::Vector3d& r, const Eigen::Vector3d& v, bool heading_only, const Density& density) {
  double s = 0.0;
  for (int c = heading_only ? 2 : 0; c < 3; ++c) s += density(r[c], v[c]);
  return s;
}

// The stall mixture's two terms for a window's residual: log(1 − p) + `moving` (its log-density
// without a stall) and log p + the log-density of the residual less the stall's loss (the
// fraction f of the predicted translation).
std::pair<double, double> stall_mixture_terms(const StallOdds& s, const WindowResidual& res, double moving,
                                              const Density& density) {
  const Eigen::Vector3d shift{-s.fraction * res.prediction.x, -s.fraction * res.prediction.y, 0.0};
  return {std::log1p(-s.p) + moving, std::log(s.p) + log_density(res.r - shift, res.variance, false, density)};
}

}  // namespace

double component_log_density(double r, double v, double dof) { return Density(dof)(r, v); }

double negative_log_likelihood(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index,
                               WindowCache* cache) {
  double nll = 0.0;
  const std::size_t n = index.empty() ? d.windows.size() : index.size();
  const double b = wheelbase_or_default(d) * m.E_b;
  // Drive stalls: the residuals of the mixture's components are taken from the prediction
  // without stalls (m_moving), not from the mean prediction.
  const bool stalls = has_stalls(d, m) && d.reference != ReferenceKind::kCompass;
  OdometryModel m_moving = m;
  m_moving.stall_rate = 0.0;
  const OdometryModel& mean_model = stalls ? m_moving : m;
  const Density density(m.dof);
  auto* predictions = cache != nullptr ? &cache->predictions(mean_model) : nullptr;
  auto* references = cache != nullptr ? &cache->references(mean_model) : nullptr;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t wi = index.empty() ? k : index[k];
    const MotionWindow& w = d.windows[wi];
    WindowResidual res;
    if (cache != nullptr) {
      const std::optional<Pose2>& ref = (*references)[wi];
      auto& pred = (*predictions)[wi];
      if (ref && !pred) {
        pred = d.odometry == OdometryKind::kPose
                   ? predict_window(d, w, mean_model, cache->increments(wi, mean_model.drive_tau))
                   : predict_window(d, w, mean_model, nullptr);
      }
      res = residual_of(d, w, mean_model, ref, ref ? *pred : Pose2());
    } else {
      res = window_residual(d, w, mean_model);
    }
    if (!res.valid) {
      nll -= log_density(Eigen::Vector3d::Zero(), res.variance, d.reference == ReferenceKind::kCompass, density);
      continue;
    }
    double ll = log_density(res.r, res.variance, res.heading_only, density);
    if (m.slip_rate > 0.0 && m.slip_loss != 0.0 && d.odometry == OdometryKind::kEncoder && w.last > w.first) {
      const double p = 1.0 - std::exp(-m.slip_rate * 0.5 * w.wheel_travel);
      if (p > 0.0) {
        const auto [ul, ur] = mean_wheel_steps(d, w);
        const Eigen::Vector3d shift_left{-m.slip_loss * ul / 2.0, 0.0, m.slip_loss * ul / b};
        const Eigen::Vector3d shift_right{-m.slip_loss * ur / 2.0, 0.0, -m.slip_loss * ur / b};
        const double l0 = std::log1p(-p) + ll;
        const double l1 = std::log(0.5 * p) + log_density(res.r - shift_left, res.variance, res.heading_only, density);
        const double l2 = std::log(0.5 * p) + log_density(res.r - shift_right, res.variance, res.heading_only, density);
        const double mx = std::max({l0, l1, l2});
        ll = mx + std::log(std::exp(l0 - mx) + std::exp(l1 - mx) + std::exp(l2 - mx));
      }
    }
    if (stalls && !res.heading_only) {
      const StallOdds s = stall_odds(d, w, m);
      if (s.p > 0.0) {
        const auto [l0, l1] = stall_mixture_terms(s, res, ll, density);
        const double mx = std::max(l0, l1);
        ll = mx + std::log(std::exp(l0 - mx) + std::exp(l1 - mx));
      }
    }
    nll -= ll;
  }
  return nll;
}

std::vector<std::optional<double>> stall_posteriors(const MotionData& d, const OdometryModel& m) {
  std::vector<std::optional<double>> posterior(d.windows.size());
  if (!has_stalls(d, m) || d.reference == ReferenceKind::kCompass) return posterior;
  OdometryModel m_moving = m;
  m_moving.stall_rate = 0.0;
  const Density density(m.dof);
  for (std::size_t wi = 0; wi < d.windows.size(); ++wi) {
    const MotionWindow& w = d.windows[wi];
    const WindowResidual res = window_residual(d, w, m_moving);
    if (!res.valid || res.heading_only) continue;
    const StallOdds s = stall_odds(d, w, m);
    if (!(s.p > 0.0)) continue;
    if (std::abs(s.fraction * res.prediction.x) < kVisibleStallSigmas * std::sqrt(res.variance.x())) continue;
    const auto [l0, l1] = stall_mixture_terms(s, res, log_density(res.r, res.variance, false, density), density);
    posterior[wi] = 1.0 / (1.0 + std::exp(l0 - l1));
  }
  return posterior;
}

double mean_distance_scale(const MotionData& d, const OdometryModel& m) {
  double model = 0.0, logged = 0.0;
  for (const auto& w : d.windows) {
    const Pose2 a = predict_window(d, w, m), b = predict_window(d, w, OdometryModel{});
    model += std::hypot(a.x, a.y);
    logged += std::hypot(b.x, b.y);
  }
  return logged > 0.0 ? model / logged : 1.0;
}

RelativePoseError relative_pose_error(const MotionData& d, const OdometryModel& m,
                                      const std::vector<std::size_t>& index, std::size_t chain) {
  RelativePoseError e;
  double st = 0.0, sh = 0.0;
  const std::size_t step = d.reference == ReferenceKind::kRelations ? 1 : std::max<std::size_t>(chain, 1);
  for (std::size_t k = 0; k + step <= index.size(); k += step) {
    Pose2 pred, ref;
    bool ok = true;
    for (std::size_t j = k; j < k + step && ok; ++j) {
      const MotionWindow& w = d.windows[index[j]];
      if (j > k && d.windows[index[j - 1]].t1 != w.t0) ok = false;  // not contiguous
      const auto r = reference_window(d, w, m);
      if (!r) ok = false;
      if (!ok) break;
      pred = pred * predict_window(d, w, m);
      ref = ref * *r;
    }
    if (!ok) continue;
    const double et = d.reference == ReferenceKind::kCompass ? 0.0 : std::hypot(ref.x - pred.x, ref.y - pred.y);
    const double eh = angle_diff(ref.theta, pred.theta);
    st += et * et;
    sh += eh * eh;
    ++e.segments;
  }
  if (e.segments > 0) {
    e.translation_rms = std::sqrt(st / static_cast<double>(e.segments));
    e.heading_rms = std::sqrt(sh / static_cast<double>(e.segments));
  }
  return e;
}

}  // namespace locbench::diagnosis
