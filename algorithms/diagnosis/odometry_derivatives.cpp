#include "algorithms/diagnosis/odometry_derivatives.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "algorithms/diagnosis/hyper_dual.h"
#include "core/angle.h"
#include "core/units.h"

namespace locbench::diagnosis {

double digamma(double x) {
  double r = 0.0;
  while (x < 8.0) {
    r -= 1.0 / x;
    x += 1.0;
  }
  const double f = 1.0 / (x * x);
  return r + std::log(x) - 0.5 / x -
         f * (1.0 / 12 - f * (1.0 / 120 - f * (1.0 / 252 - f * (1.0 / 240 - f * (1.0 / 132)))));
}

double trigamma(double x) {
  double r = 0.0;
  while (x < 8.0) {
    r += 1.0 / (x * x);
    x += 1.0;
  }
  const double f = 1.0 / (x * x);
  return r + 1.0 / x + 0.5 * f +
         (1.0 / x) * f * (1.0 / 6 - f * (1.0 / 30 - f * (1.0 / 42 - f * (1.0 / 30 - f * (5.0 / 66)))));
}

namespace {
// A namespace of its own: in unity builds this file shares a unit with odometry_model.cpp.
namespace ad {

using Field = double OdometryModel::*;
using Mean = HyperDual<5>;  // over the fitted mean-motion fields (at most 5 act on one kind of odometry)
using Full = HyperDual<kMaxDifferentiatedFields>;

// The fields that move the window prediction (with stalls taken out of the mean model).
constexpr std::array<Field, 8> kMeanFields{&OdometryModel::E_d,
                                           &OdometryModel::E_b,
                                           &OdometryModel::E_o,
                                           &OdometryModel::velocity_scale,
                                           &OdometryModel::turn_rate_scale,
                                           &OdometryModel::turn_rate_bias,
                                           &OdometryModel::speed_slope,
                                           &OdometryModel::drive_tau};

// A model field as a number: a variable when fitted, a constant otherwise.
template <class T>
struct Seeded {
  const OdometryModel& m;
  const std::vector<Field>& fields;  // the differentiated fields, in variable order
  int n;
  T operator()(Field f) const {
    for (int i = 0; i < static_cast<int>(fields.size()); ++i) {
      if (fields[i] == f) return T::variable(m.*f, i, n);
    }
    return T(m.*f);
  }
};

template <class T>
struct PoseT {
  T x{0.0}, y{0.0}, theta{0.0};
};

template <class T>
PoseT<T> advance(const PoseT<T>& p, const T& dd, const T& dth) {
  const T half = 0.5 * dth;
  const T chord = std::abs(value_of(half)) < 1e-6 ? dd : dd * sin(half) / half;
  const T heading = p.theta + half;
  T s, c;
  sincos(heading, s, c);
  return {p.x + chord * c, p.y + chord * s, p.theta + dth};
}

// A number over τ alone.
using TauNumber = HyperDual<1>;

// τ's place among the mean fields (−1: not fitted).
int tau_index(const Seeded<Mean>& s) {
  const auto it = std::find(s.fields.begin(), s.fields.end(), &OdometryModel::drive_tau);
  return it == s.fields.end() ? -1 : static_cast<int>(it - s.fields.begin());
}

// A number over τ as a number over the n mean fields, τ the at-th.
Mean lift_tau(const TauNumber& x, int at, int n) {
  if (x.n == 0) return Mean(x.v);
  Mean r = Mean::zero(n);
  r.v = x.v;
  r.g[at] = x.g[0];
  r.h[at * n - at * (at - 1) / 2] = x.h[0];
  return r;
}

// predict_window of odometry_model.cpp without stalls (the likelihood's mean model). `increments`
// (pose odometry, τ not differentiated): the window's drive_increments, constants here.
PoseT<Mean> predict(const MotionData& d, const MotionWindow& w, const Seeded<Mean>& s, const double* increments) {
  PoseT<Mean> p;
  if (d.odometry == OdometryKind::kEncoder) {
    const Mean e_d = s(&OdometryModel::E_d), e_o = s(&OdometryModel::E_o);
    const Mean cl = d.nominal.meters_per_tick_left * e_o * 2.0 / (1.0 + e_d);
    const Mean cr = d.nominal.meters_per_tick_right * e_o * 2.0 * e_d / (1.0 + e_d);
    const Mean b = d.nominal.wheelbase * s(&OdometryModel::E_b);
    for (std::size_t i = w.first; i < w.last; ++i) {
      const Mean ul = cl * d.steps[i].a, ur = cr * d.steps[i].b;
      p = advance(p, 0.5 * (ul + ur), (ur - ul) / b);
    }
    return p;
  }
  const Mean tau = s(&OdometryModel::drive_tau);
  const Mean velocity_scale = s(&OdometryModel::velocity_scale), speed_slope = s(&OdometryModel::speed_slope);
  const Mean turn_scale = s(&OdometryModel::turn_rate_scale), turn_bias = s(&OdometryModel::turn_rate_bias);
  if (increments != nullptr) {
    for (std::size_t i = w.first; i < w.last; ++i) {
      const auto [dt, v, rate] = step_rates(d.steps[i]);
      const double* inc = increments + 2 * (i - w.first);
      const Mean scale = velocity_scale + speed_slope * std::abs(v);
      p = advance(p, scale * Mean(inc[0]), turn_scale * Mean(inc[1]) + turn_bias * dt);
    }
    return p;
  }
  // The drive's increments depend on τ alone: they are run in as numbers over τ only and lifted
  // to the mean fields per step (a run-in over all mean fields costs a third more per call).
  const int at = tau_index(s);
  const TauNumber t = at >= 0 ? TauNumber::variable(tau.v, 0, 1) : TauNumber(tau.v);
  const DriveRunIn run_in = drive_run_in(d, w, tau.v);
  // t_s = (w's first step's start) − 4τ moves with τ unless clamped; the state there is the
  // interpolated rate.
  const TauNumber start = run_in.clamped ? TauNumber(run_in.t) : d.steps[w.first].t0 - 4.0 * t;
  const TauNumber moved = start - run_in.t;
  TauNumber u = run_in.v + run_in.v_slope * moved, omega = run_in.rate + run_in.rate_slope * moved;
  for (std::size_t i = run_in.step; i < w.last; ++i) {
    const auto& st = d.steps[i];
    const auto [full_dt, v, rate] = step_rates(st);
    const TauNumber dt = i == run_in.step && i < w.first ? st.t1 - start : TauNumber(full_dt);
    TauNumber dd(st.a), dth(st.b);
    if (tau.v > 0.0 && dt.v > 0.0) {
      const TauNumber decay = exp(-dt / t);
      dd = v * dt + (u - v) * t * (1.0 - decay);
      u = v + (u - v) * decay;
      dth = rate * dt + (omega - rate) * t * (1.0 - decay);
      omega = rate + (omega - rate) * decay;
    }
    if (i < w.first) continue;
    const Mean scale = velocity_scale + speed_slope * std::abs(v);
    p = advance(p, scale * lift_tau(dd, at, s.n), turn_scale * lift_tau(dth, at, s.n) + turn_bias * full_dt);
  }
  return p;
}

// A prediction over the mean fields as a number over all fitted fields.
Full lift(const Mean& a, const std::vector<int>& to_full, int n) {
  Full r = Full::zero(n);
  r.v = a.v;
  if (a.n == 0) return r;
  for (int i = 0; i < a.n; ++i) {
    r.g[to_full[i]] = a.g[i];
    for (int j = i; j < a.n; ++j) {
      const int fi = std::min(to_full[i], to_full[j]), fj = std::max(to_full[i], to_full[j]);
      r.h[fi * n - fi * (fi - 1) / 2 + (fj - fi)] = a.hessian(i, j);
    }
  }
  return r;
}

struct Density {
  Full dof;
  bool student;
  Full constant{0.0};
  Full half_dof1{0.0};  // ½(ν + 1)
  explicit Density(const Full& nu) : dof(nu), student(nu.v > 0.0) {
    if (!student) return;
    constant = lgamma(0.5 * (nu + 1.0)) - lgamma(0.5 * nu) - 0.5 * log(nu * kPi);
    half_dof1 = 0.5 * (nu + 1.0);
  }
  // The terms that depend on the squared scale v alone (the same v in every window without noise
  // growth, so computed once then).
  struct Scale {
    Full v, head, dof_v;
  };
  Scale scale(const Full& v) const {
    if (!student) return {v, log(2.0 * kPi * v), Full(0.0)};
    return {v, constant - 0.5 * log(v), dof * v};
  }
  // The log-density of r: −½(r²/v + log 2πv), or the Student-t's
  // constant − ½·log v − ½(ν + 1)·log1p(r²/(ν·v)), evaluated in that order.
  Full operator()(const Full& r, const Scale& s) const {
    if (!student) return -0.5 * (r * r / s.v + s.head);
    return s.head - half_dof1 * log1p(r * r / s.dof_v);
  }
};
using Scales = std::array<Density::Scale, 3>;

Full log_density(const std::array<Full, 3>& r, const Scales& v, bool heading_only, const Density& density) {
  Full s(0.0);
  for (int c = heading_only ? 2 : 0; c < 3; ++c) s = s + density(r[c], v[c]);
  return s;
}

std::array<Full, 3> shifted(const std::array<Full, 3>& r, const std::array<Full, 3>& shift) {
  return {r[0] - shift[0], r[1] - shift[1], r[2] - shift[2]};
}

// log Σ exp(l_i), with the largest value factored out as in odometry_model.cpp.
template <std::size_t N>
Full log_sum_exp(const std::array<Full, N>& l) {
  std::size_t mx = 0;
  for (std::size_t i = 1; i < l.size(); ++i) {
    if (l[i].v > l[mx].v) mx = i;
  }
  Full sum(0.0);
  for (const Full& x : l) sum = sum + exp(x - l[mx]);
  return l[mx] + log(sum);
}

}  // namespace ad
}  // namespace

namespace {

// The fitted mean fields, and where each sits among all fitted fields.
struct MeanFields {
  std::vector<ad::Field> fields;
  std::vector<int> to_full;
};

MeanFields mean_fields_of(const std::vector<ad::Field>& fields) {
  MeanFields out;
  for (int i = 0; i < static_cast<int>(fields.size()); ++i) {
    if (std::find(ad::kMeanFields.begin(), ad::kMeanFields.end(), fields[i]) != ad::kMeanFields.end()) {
      out.fields.push_back(fields[i]);
      out.to_full.push_back(i);
    }
  }
  return out;
}

// The noise parameters, seeded as variables where fitted.
struct NoiseSeeds {
  ad::Full b;  // the wheelbase [m]
  ad::Full sx, sy, st, k2;
  ad::Full slip_rate, slip_loss;
  ad::Full stall_rate, stall_duration;
};

NoiseSeeds noise_seeds(const ad::Seeded<ad::Full>& seed, double base) {
  return {base * seed(&OdometryModel::E_b),  seed(&OdometryModel::sigma_x),    seed(&OdometryModel::sigma_y),
          seed(&OdometryModel::sigma_theta), seed(&OdometryModel::k2),         seed(&OdometryModel::slip_rate),
          seed(&OdometryModel::slip_loss),   seed(&OdometryModel::stall_rate), seed(&OdometryModel::stall_duration)};
}

// The reference of window `wi`, from the cache when there is one.
std::optional<Pose2> window_reference(const MotionData& d, std::size_t wi, const OdometryModel& mean_model,
                                      std::vector<std::optional<std::optional<Pose2>>>* references) {
  const MotionWindow& w = d.windows[wi];
  if (references == nullptr) return reference_window(d, w, mean_model);
  auto& cached = (*references)[wi];
  if (!cached) cached = reference_window(d, w, mean_model);
  return *cached;
}

// The predicted pose of window `wi`: values (cached) when no mean field is fitted, else
// differentiated in the mean fields and lifted to all fitted fields.
struct Prediction {
  const MotionData& d;
  const OdometryModel& mean_model;
  const ad::Seeded<ad::Mean>& mean_seed;
  const MeanFields& mean;
  int n;
  WindowCache* cache;
  std::vector<std::optional<Pose2>>* predictions;
  bool drive_tau_fitted;

  ad::PoseT<ad::Full> operator()(std::size_t wi, std::vector<double>& buffer) const {
    using namespace ad;
    const MotionWindow& w = d.windows[wi];
    if (mean.fields.empty()) {
      Pose2 p;
      if (predictions != nullptr) {
        auto& cached = (*predictions)[wi];
        if (!cached) {
          cached = d.odometry == OdometryKind::kPose
                       ? predict_window(d, w, mean_model, cache->increments(wi, mean_model.drive_tau))
                       : predict_window(d, w, mean_model, nullptr);
        }
        p = *cached;
      } else {
        p = predict_window(d, w, mean_model);
      }
      return {Full(p.x), Full(p.y), Full(p.theta)};
    }
    const double* increments = nullptr;
    if (d.odometry == OdometryKind::kPose && !drive_tau_fitted) {
      if (cache != nullptr) {
        increments = cache->increments(wi, mean_model.drive_tau);
      } else {
        buffer.resize(2 * (w.last - w.first));
        drive_increments(d, w, mean_model.drive_tau, buffer.data());
        increments = buffer.data();
      }
    }
    const PoseT<Mean> pm = predict(d, w, mean_seed, increments);
    return {lift(pm.x, mean.to_full, n), lift(pm.y, mean.to_full, n), lift(pm.theta, mean.to_full, n)};
  }
};

// The window's log-likelihood as a mixture with a slip of either wheel (§3.2).
ad::Full with_slip(const ad::Full& ll, const std::array<ad::Full, 3>& r, const MotionData& d, const MotionWindow& w,
                   const NoiseSeeds& s, const ad::Scales& variance, bool heading_only, const ad::Density& density) {
  using namespace ad;
  const Full p = 1.0 - exp(-s.slip_rate * 0.5 * w.wheel_travel);
  if (!(p.v > 0.0)) return ll;
  const auto [ul, ur] = mean_wheel_steps(d, w);
  const std::array<Full, 3> left{-s.slip_loss * ul / 2.0, Full(0.0), s.slip_loss * ul / s.b};
  const std::array<Full, 3> right{-s.slip_loss * ur / 2.0, Full(0.0), -s.slip_loss * ur / s.b};
  const Full half_p = log(0.5 * p);
  return log_sum_exp<3>({log1p(-p) + ll, half_p + log_density(shifted(r, left), variance, heading_only, density),
                         half_p + log_density(shifted(r, right), variance, heading_only, density)});
}

// The window's log-likelihood as a mixture with a drive stall that shortens the window's motion.
ad::Full with_stall(const ad::Full& ll, const std::array<ad::Full, 3>& r, const ad::PoseT<ad::Full>& pred,
                    const MotionWindow& w, const NoiseSeeds& s, const ad::Scales& variance,
                    const ad::Density& density) {
  using namespace ad;
  const double span = w.t1 - w.t0;
  if (!(span > 0.0)) return ll;
  const Full p = -expm1(-s.stall_rate * span);
  const Full ratio = s.stall_duration / span;
  const Full fraction = ratio.v < 1.0 ? ratio : Full(1.0);
  if (!(p.v > 0.0)) return ll;
  const std::array<Full, 3> shift{-fraction * pred.x, -fraction * pred.y, Full(0.0)};
  return log_sum_exp<2>({log1p(-p) + ll, log(p) + log_density(shifted(r, shift), variance, false, density)});
}

std::optional<double> derivatives_of(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index,
                                     const std::vector<double OdometryModel::*>& fields, Eigen::VectorXd& gradient,
                                     Eigen::MatrixXd& hessian, WindowCache* cache) {
  using namespace ad;
  const int n = static_cast<int>(fields.size());
  if (n > kMaxDifferentiatedFields) return std::nullopt;
  if (std::find(fields.begin(), fields.end(), &OdometryModel::time_offset) != fields.end()) return std::nullopt;
  const bool has_stalls = d.odometry == OdometryKind::kPose && m.stall_rate > 0.0 && m.stall_duration > 0.0;
  const bool stalls = has_stalls && d.reference != ReferenceKind::kCompass;
  if (has_stalls && !stalls) return std::nullopt;  // stalls would move the mean prediction
  OdometryModel mean_model = m;
  if (stalls) mean_model.stall_rate = 0.0;

  const MeanFields mean = mean_fields_of(fields);
  if (mean.fields.size() > static_cast<std::size_t>(Mean::kCapacity)) return std::nullopt;
  const Seeded<Mean> mean_seed{mean_model, mean.fields, static_cast<int>(mean.fields.size())};
  const Seeded<Full> seed{m, fields, n};

  const double base = d.nominal.wheelbase > 0.0 ? d.nominal.wheelbase : 0.5;
  const Density density(seed(&OdometryModel::dof));
  const NoiseSeeds s = noise_seeds(seed, base);
  auto* references = cache != nullptr ? &cache->references(mean_model) : nullptr;
  auto* predictions = cache != nullptr && mean.fields.empty() ? &cache->predictions(mean_model) : nullptr;
  const bool drive_tau_fitted =
      std::find(mean.fields.begin(), mean.fields.end(), &OdometryModel::drive_tau) != mean.fields.end();
  const Prediction predicted{d, mean_model, mean_seed, mean, n, cache, predictions, drive_tau_fitted};

  std::vector<double> buffer;  // drive increments without a cache
  // Without noise growth (k² = 0, not fitted) every window has the same variance.
  const bool constant_variance = s.k2.n == 0 && s.k2.v == 0.0;
  const Full sxx = s.sx * s.sx, syy = s.sy * s.sy, stt = s.st * s.st;
  Scales variance;
  Full nll(0.0);
  const std::size_t count = index.empty() ? d.windows.size() : index.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t wi = index.empty() ? k : index[k];
    const MotionWindow& w = d.windows[wi];
    const std::optional<Pose2> ref = window_reference(d, wi, mean_model, references);
    if (!constant_variance || k == 0) {
      const Full growth = s.k2 * w.wheel_travel;
      variance = {density.scale(sxx + growth / 4.0), density.scale(syy + growth / 4.0),
                  density.scale(stt + growth / (base * base))};
    }
    const bool heading_only = d.reference == ReferenceKind::kCompass;
    if (!ref) {
      const std::array<Full, 3> zero{Full(0.0), Full(0.0), Full(0.0)};
      nll = nll - log_density(zero, variance, heading_only, density);
      continue;
    }
    const PoseT<Full> pred = predicted(wi, buffer);
    // r = reference − prediction; the heading difference wrapped by its value.
    Full rt = -pred.theta;
    rt.v = angle_diff(ref->theta, pred.theta.v);
    std::array<Full, 3> r{ref->x - pred.x, ref->y - pred.y, rt};
    if (heading_only) r[0] = r[1] = Full(0.0);
    Full ll = log_density(r, variance, heading_only, density);
    if (m.slip_rate > 0.0 && m.slip_loss != 0.0 && d.odometry == OdometryKind::kEncoder && w.last > w.first) {
      ll = with_slip(ll, r, d, w, s, variance, heading_only, density);
    }
    if (stalls && !heading_only) ll = with_stall(ll, r, pred, w, s, variance, density);
    nll = nll - ll;
  }
  gradient.resize(n);
  hessian.resize(n, n);
  for (int i = 0; i < n; ++i) {
    gradient[i] = nll.n == 0 ? 0.0 : nll.g[i];
    for (int j = 0; j < n; ++j) hessian(i, j) = nll.n == 0 ? 0.0 : nll.hessian(i, j);
  }
  return nll.v;
}

}  // namespace

std::optional<double> negative_log_likelihood_derivatives(const MotionData& d, const OdometryModel& m,
                                                          const std::vector<std::size_t>& index,
                                                          const std::vector<double OdometryModel::*>& fields,
                                                          Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian,
                                                          WindowCache* cache) {
  return derivatives_of(d, m, index, fields, gradient, hessian, cache);
}

}  // namespace locbench::diagnosis
