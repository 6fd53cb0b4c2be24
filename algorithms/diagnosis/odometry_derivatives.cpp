#include "algorithms/diagnosis/odometry_derivatives.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "algorithms/diagnosis/component_density.h"
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

// The window pose of pose odometry over its mean fields by the chain rule. Each step adds
// T = a·K(b/2)·(cos φ, sin φ) with a = (scale + slope·|v|)·ΔD(τ) the step's distance,
// b = turn_scale·Δθ(τ) + turn_bias·Δt its turn, φ the heading at its middle and K(h) = sin h / h
// the chord's factor (eq. 1.3 with the arc's chord); T's derivatives in (a, b, φ) are closed form,
// and (a, b, φ) are at most quadratic in the five fields (scale, slope, turn scale, turn bias, τ).
// The values are computed as predict_window computes them.
class ChainPose {
 public:
  enum Param { kScale, kSlope, kTurnScale, kTurnBias, kTau, kParams };

  // `at[p]`: param p's place among the fitted mean fields (−1: not fitted; its derivatives are
  // not accumulated).
  ChainPose(double scale, double slope, double turn_scale, double turn_bias, const std::array<int, kParams>& at)
      : scale_(scale), slope_(slope), turn_scale_(turn_scale), turn_bias_(turn_bias) {
    for (int p = 0; p < kParams; ++p) {
      if (at[p] >= 0) active_[active_count_++] = p;
    }
  }

  // One step: its logged distance and turn increments through the drive response (value, ∂τ, ∂²τ),
  // its duration and its logged speed.
  void step(const HyperDual<1>& dd, const HyperDual<1>& dth, double dt, double speed) {
    const double d1 = dd.n ? dd.g[0] : 0.0, d2 = dd.n ? dd.h[0] : 0.0;
    const double t1 = dth.n ? dth.g[0] : 0.0, t2 = dth.n ? dth.h[0] : 0.0;
    const double s = scale_ + slope_ * speed;
    const double a = s * dd.v;
    const double b = turn_scale_ * dth.v + turn_bias_ * dt;
    const double half = 0.5 * b;
    const double phi = theta_ + half;
    // K(h) with predict_window's value; its derivatives by the series where sin h / h cancels.
    const double sh = std::sin(half);
    const double k = std::abs(half) < 1e-6 ? 1.0 : sh / half;
    double k1, k2;
    if (std::abs(half) < 1e-2) {
      const double h2 = half * half;
      k1 = -half / 3.0 + half * h2 / 30.0;
      k2 = -1.0 / 3.0 + h2 / 10.0;
    } else {
      const double ch = std::cos(half);
      k1 = (half * ch - sh) / (half * half);
      k2 = -sh / half - 2.0 * ch / (half * half) + 2.0 * sh / (half * half * half);
    }
    const double sn = std::sin(phi), cs = std::cos(phi);
    const double chord = std::abs(half) < 1e-6 ? a : a * sh / half;
    x_ += chord * cs;
    y_ += chord * sn;
    // J: ∂(a, b, φ)/∂params, and their second derivatives (only τ's cross terms).
    const double run1 = turn1_ + 0.5 * t1, run2 = turn2_ + 0.5 * t2;  // φ's Σ Δθ' and Σ Δθ'' to the middle
    double J[3][kParams] = {{dd.v, speed * dd.v, 0.0, 0.0, s * d1},
                            {0.0, 0.0, dth.v, dt, turn_scale_ * t1},
                            {0.0, 0.0, turn0_ + 0.5 * dth.v, time_ + 0.5 * dt, turn_scale_ * run1}};
    // T's derivatives in (a, b, φ) for x (cos) and y (sin); ∂/∂b = ½K'·…, ∂²/∂b² = ¼K''·….
    const double gx[3] = {k * cs, 0.5 * a * k1 * cs, -a * k * sn};
    const double gy[3] = {k * sn, 0.5 * a * k1 * sn, a * k * cs};
    const double hx[3][3] = {{0.0, 0.5 * k1 * cs, -k * sn},
                             {0.5 * k1 * cs, 0.25 * a * k2 * cs, -0.5 * a * k1 * sn},
                             {-k * sn, -0.5 * a * k1 * sn, -a * k * cs}};
    const double hy[3][3] = {{0.0, 0.5 * k1 * sn, k * cs},
                             {0.5 * k1 * sn, 0.25 * a * k2 * sn, 0.5 * a * k1 * cs},
                             {k * cs, 0.5 * a * k1 * cs, -a * k * sn}};
    add(gx, hx, J, gx_, hx_);
    add(gy, hy, J, gy_, hy_);
    // Second derivatives of a, b, φ in the params (symmetric pairs with τ).
    const double a_st = d1, a_lt = speed * d1, a_tt = s * d2;
    const double b_tt = turn_scale_ * t2, b_ct = t1;  // (turn scale, τ)
    const double f_tt = turn_scale_ * run2, f_ct = run1;
    for (int c = 0; c < 2; ++c) {
      const double* g = c == 0 ? gx : gy;
      double(&h)[kParams][kParams] = c == 0 ? hx_ : hy_;
      h[kScale][kTau] += g[0] * a_st;
      h[kTau][kScale] += g[0] * a_st;
      h[kSlope][kTau] += g[0] * a_lt;
      h[kTau][kSlope] += g[0] * a_lt;
      h[kTau][kTau] += g[0] * a_tt + g[1] * b_tt + g[2] * f_tt;
      h[kTurnScale][kTau] += g[1] * b_ct + g[2] * f_ct;
      h[kTau][kTurnScale] += g[1] * b_ct + g[2] * f_ct;
    }
    theta_ += b;
    turn0_ += dth.v;
    turn1_ += t1;
    turn2_ += t2;
    time_ += dt;
  }

  // The pose as numbers over the fitted mean fields; `at[p]` is param p's place among them (−1: not fitted).
  template <class Number>
  PoseT<Number> pose(const std::array<int, kParams>& at, int n) const {
    PoseT<Number> out;
    double gt[kParams] = {0.0, 0.0, turn0_, time_, turn_scale_ * turn1_};
    double ht[kParams][kParams] = {};
    ht[kTurnScale][kTau] = ht[kTau][kTurnScale] = turn1_;
    ht[kTau][kTau] = turn_scale_ * turn2_;
    out.x = number<Number>(x_, gx_, hx_, at, n);
    out.y = number<Number>(y_, gy_, hy_, at, n);
    out.theta = number<Number>(theta_, gt, ht, at, n);
    return out;
  }

 private:
  // g·J and Jᵀ·h·J over the fitted params.
  void add(const double (&g)[3], const double (&h)[3][3], const double (&J)[3][kParams], double (&gs)[kParams],
           double (&hs)[kParams][kParams]) const {
    double m[3][kParams];  // h·J
    for (int u = 0; u < 3; ++u) {
      for (int a = 0; a < active_count_; ++a) {
        const int p = active_[a];
        m[u][p] = h[u][0] * J[0][p] + h[u][1] * J[1][p] + h[u][2] * J[2][p];
      }
    }
    for (int a = 0; a < active_count_; ++a) {
      const int p = active_[a];
      gs[p] += g[0] * J[0][p] + g[1] * J[1][p] + g[2] * J[2][p];
      for (int b = 0; b < active_count_; ++b) {
        const int q = active_[b];
        hs[p][q] += J[0][p] * m[0][q] + J[1][p] * m[1][q] + J[2][p] * m[2][q];
      }
    }
  }
  template <class Number>
  static Number number(double v, const double (&g)[kParams], const double (&h)[kParams][kParams],
                       const std::array<int, kParams>& at, int n) {
    if (n == 0) return Number(v);
    Number r = Number::zero(n);
    r.v = v;
    for (int p = 0; p < kParams; ++p) {
      if (at[p] < 0) continue;
      r.g[at[p]] = g[p];
      for (int q = 0; q < kParams; ++q) {
        if (at[q] < at[p]) continue;
        r.h[at[p] * n - at[p] * (at[p] - 1) / 2 + (at[q] - at[p])] = h[p][q];
      }
    }
    return r;
  }

  double scale_, slope_, turn_scale_, turn_bias_;
  int active_[kParams] = {};
  int active_count_ = 0;
  double x_ = 0.0, y_ = 0.0, theta_ = 0.0;
  double turn0_ = 0.0, turn1_ = 0.0, turn2_ = 0.0, time_ = 0.0;  // Σ Δθ, Σ ∂τΔθ, Σ ∂²τΔθ, Σ Δt so far
  double gx_[kParams] = {}, gy_[kParams] = {};
  double hx_[kParams][kParams] = {}, hy_[kParams][kParams] = {};
};

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
  const auto field = [&](double OdometryModel::*f) {
    const auto it = std::find(s.fields.begin(), s.fields.end(), f);
    return it == s.fields.end() ? -1 : static_cast<int>(it - s.fields.begin());
  };
  const std::array<int, ChainPose::kParams> at{
      field(&OdometryModel::velocity_scale), field(&OdometryModel::speed_slope), field(&OdometryModel::turn_rate_scale),
      field(&OdometryModel::turn_rate_bias), field(&OdometryModel::drive_tau)};
  ChainPose chain(s.m.velocity_scale, s.m.speed_slope, s.m.turn_rate_scale, s.m.turn_rate_bias, at);
  if (increments != nullptr) {
    for (std::size_t i = w.first; i < w.last; ++i) {
      const auto [dt, v, rate] = step_rates(d.steps[i]);
      const double* inc = increments + 2 * (i - w.first);
      chain.step(TauNumber(inc[0]), TauNumber(inc[1]), dt, std::abs(v));
    }
    return chain.pose<Mean>(at, s.n);
  }
  // The drive's increments depend on τ alone: they are run in as numbers over τ only.
  const double tau = s.m.drive_tau;
  const TauNumber t = at[ChainPose::kTau] >= 0 ? TauNumber::variable(tau, 0, 1) : TauNumber(tau);
  const DriveRunIn run_in = drive_run_in(d, w, tau);
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
    if (tau > 0.0 && dt.v > 0.0) {
      const TauNumber decay = exp(-dt / t);
      dd = v * dt + (u - v) * t * (1.0 - decay);
      u = v + (u - v) * decay;
      dth = rate * dt + (omega - rate) * t * (1.0 - decay);
      omega = rate + (omega - rate) * decay;
    }
    if (i < w.first) continue;
    chain.step(dd, dth, full_dt, std::abs(v));
  }
  return chain.pose<Mean>(at, s.n);
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
                                      const std::vector<std::optional<Pose2>>* references) {
  if (references == nullptr) return reference_window(d, d.windows[wi], mean_model);
  return (*references)[wi];
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
    const PoseT<Mean> pm = mean_pose(wi, buffer);
    if (mean.fields.empty()) return {Full(pm.x.v), Full(pm.y.v), Full(pm.theta.v)};
    return {lift(pm.x, mean.to_full, n), lift(pm.y, mean.to_full, n), lift(pm.theta, mean.to_full, n)};
  }

  // The same over the fitted mean fields only (constants when none is fitted).
  ad::PoseT<ad::Mean> mean_pose(std::size_t wi, std::vector<double>& buffer) const {
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
      return {Mean(p.x), Mean(p.y), Mean(p.theta)};
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
    return predict(d, w, mean_seed, increments);
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

// ---------------------------------------------------------------- pose odometry by the chain rule
// Pose odometry against a position reference: a window's log-likelihood depends on the fitted
// fields only through nine inner quantities u — the predicted pose (x, y, θ), the three variances
// v, the Student-t ν, the stall probability P and the stall's fraction F. Its derivatives in u come
// from each residual component on numbers over (residual, variance, ν) and the stall mixture's
// log-sum-exp; then ∇ = Jᵀ∇_u and ∇² = Jᵀ∇²_u J + Σ_a ∂ℓ/∂u_a·∇²u_a with J = ∂u/∂fields, which
// is sparse. The same likelihood as the hyper-dual pass over all fields, at a fraction of its cost.
namespace window_terms {

using chain::Component;
enum Inner { kPx, kPy, kPtheta, kVx, kVy, kVtheta, kNu, kP, kF, kInner };
using InnerVector = Eigen::Matrix<double, kInner, 1>;
using InnerMatrix = Eigen::Matrix<double, kInner, kInner>;

// A log-likelihood term in u: its value, gradient and Hessian.
struct Term {
  double value = 0.0;
  InnerVector g = InnerVector::Zero();
  InnerMatrix h = InnerMatrix::Zero();
};

// Adds component density D whose residual x depends on the prediction p of its component with
// ∂x/∂p = dx_dp, on the stall fraction with ∂x/∂F = dx_df and ∂²x/∂p∂F = d2x_dpdf.
void add_component(Term& t, const Component& D, int p, int v, double dx_dp, double dx_df, double d2x_dpdf) {
  const double gx = D.g[0], gv = D.g[1], gn = D.g[2];
  const double hxx = D.hessian(0, 0), hxv = D.hessian(0, 1), hxn = D.hessian(0, 2);
  const double hvv = D.hessian(1, 1), hvn = D.hessian(1, 2), hnn = D.hessian(2, 2);
  t.value += D.v;
  t.g[p] += gx * dx_dp;
  t.g[v] += gv;
  t.g[kNu] += gn;
  t.g[kF] += gx * dx_df;
  auto add = [&](int a, int b, double x) {
    t.h(a, b) += x;
    if (a != b) t.h(b, a) += x;
  };
  add(p, p, hxx * dx_dp * dx_dp);
  add(p, v, hxv * dx_dp);
  add(p, kNu, hxn * dx_dp);
  add(v, v, hvv);
  add(v, kNu, hvn);
  add(kNu, kNu, hnn);
  add(kF, kF, hxx * dx_df * dx_df);
  add(p, kF, hxx * dx_dp * dx_df + gx * d2x_dpdf);
  add(kF, v, hxv * dx_df);
  add(kF, kNu, hxn * dx_df);
}

// log(e^a + e^b) of two terms.
Term log_sum_exp(const Term& a, const Term& b) {
  const double top = std::max(a.value, b.value);
  const double ea = std::exp(a.value - top), eb = std::exp(b.value - top);
  const double wa = ea / (ea + eb), wb = 1.0 - wa;
  Term t;
  t.value = top + std::log(ea + eb);
  t.g = wa * a.g + wb * b.g;
  const InnerVector diff = a.g - b.g;
  t.h = wa * a.h + wb * b.h + (wa * wb) * diff * diff.transpose();
  return t;
}

// Where each inner quantity comes from: ∂u_a/∂field as (field index, value) pairs, and the second
// derivatives of u that are not zero.
struct Jacobian {
  std::array<std::array<std::pair<int, double>, kMaxDifferentiatedFields>, kInner> rows;
  std::array<int, kInner> size{};
  void clear() { size.fill(0); }
  void add(int a, int field, double value) {
    if (field >= 0) rows[a][size[a]++] = {field, value};
  }
};

}  // namespace window_terms

// The fields a chain-rule pass handles: pose odometry's causes and noise, E_b not fitted.
bool chain_rule_applies(const MotionData& d, const std::vector<double OdometryModel::*>& fields) {
  if (d.odometry != OdometryKind::kPose || d.reference == ReferenceKind::kCompass) return false;
  static constexpr std::array<double OdometryModel::*, 12> kHandled{&OdometryModel::sigma_x,
                                                                    &OdometryModel::sigma_y,
                                                                    &OdometryModel::sigma_theta,
                                                                    &OdometryModel::k2,
                                                                    &OdometryModel::dof,
                                                                    &OdometryModel::stall_rate,
                                                                    &OdometryModel::stall_duration,
                                                                    &OdometryModel::velocity_scale,
                                                                    &OdometryModel::turn_rate_scale,
                                                                    &OdometryModel::turn_rate_bias,
                                                                    &OdometryModel::speed_slope,
                                                                    &OdometryModel::drive_tau};
  return std::all_of(fields.begin(), fields.end(),
                     [](auto f) { return std::find(kHandled.begin(), kHandled.end(), f) != kHandled.end(); });
}

// The likelihood's value, gradient and Hessian by the chain rule (chain_rule_applies).
double chain_rule_pass(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index,
                       const std::vector<double OdometryModel::*>& fields, const MeanFields& mean,
                       const Prediction& predicted, const std::vector<std::optional<Pose2>>* references, bool stalls,
                       Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
  using namespace ad;
  using namespace window_terms;
  using chain::component_density;
  using chain::StudentConstant;
  const int n = static_cast<int>(fields.size());
  auto at = [&](double OdometryModel::*f) {
    const auto it = std::find(fields.begin(), fields.end(), f);
    return it == fields.end() ? -1 : static_cast<int>(it - fields.begin());
  };
  const std::array<int, 3> i_sigma{at(&OdometryModel::sigma_x), at(&OdometryModel::sigma_y),
                                   at(&OdometryModel::sigma_theta)};
  const int i_k2 = at(&OdometryModel::k2), i_dof = at(&OdometryModel::dof);
  const int i_rate = at(&OdometryModel::stall_rate), i_duration = at(&OdometryModel::stall_duration);
  const std::array<double, 3> sigma{m.sigma_x, m.sigma_y, m.sigma_theta};
  const double b = (d.nominal.wheelbase > 0.0 ? d.nominal.wheelbase : 0.5) * m.E_b;
  const StudentConstant student(m.dof);
  const OdometryModel& mean_model = predicted.mean_model;
  const int nm = static_cast<int>(mean.fields.size());

  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  double total = 0.0;
  std::vector<double> buffer;
  Jacobian jac;
  const std::size_t count = index.empty() ? d.windows.size() : index.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t wi = index.empty() ? k : index[k];
    const MotionWindow& w = d.windows[wi];
    const std::optional<Pose2> ref = window_reference(d, wi, mean_model, references);
    // v_c = σ_c² + k²·W·(¼, ¼, 1/B²) (eq. 4.36–4.37 summed).
    const std::array<double, 3> per_k2{w.wheel_travel / 4.0, w.wheel_travel / 4.0, w.wheel_travel / (b * b)};
    std::array<double, 3> v{};
    for (int c = 0; c < 3; ++c) v[c] = sigma[c] * sigma[c] + m.k2 * per_k2[c];
    jac.clear();
    for (int c = 0; c < 3; ++c) {
      jac.add(kVx + c, i_sigma[c], 2.0 * sigma[c]);
      jac.add(kVx + c, i_k2, per_k2[c]);
    }
    jac.add(kNu, i_dof, 1.0);
    Term ll;
    PoseT<Mean> pm;
    bool stalled_mixture = false;
    double span = 0.0, decay = 1.0;
    if (!ref) {  // not covered: the constant of a perfect fit
      for (int c = 0; c < 3; ++c) add_component(ll, component_density(0.0, v[c], student), kPx + c, kVx + c, 0, 0, 0);
    } else {
      pm = predicted.mean_pose(wi, buffer);
      const std::array<const Mean*, 3> pose{&pm.x, &pm.y, &pm.theta};
      for (int c = 0; c < 3; ++c) {
        if (pose[c]->n == 0) continue;
        for (int q = 0; q < nm; ++q) jac.add(kPx + c, mean.to_full[q], pose[c]->g[q]);
      }
      // r = reference − prediction; the heading difference wrapped by its value.
      const std::array<double, 3> r{ref->x - pm.x.v, ref->y - pm.y.v, angle_diff(ref->theta, pm.theta.v)};
      for (int c = 0; c < 3; ++c) add_component(ll, component_density(r[c], v[c], student), kPx + c, kVx + c, -1, 0, 0);
      span = w.t1 - w.t0;
      const double p = stalls && span > 0.0 ? -std::expm1(-m.stall_rate * span) : 0.0;
      if (p > 0.0) {
        // The stall mixture: (1 − P)·g(r) + P·g(r + F·t̂), t̂ the predicted translation, F = min(duration/T, 1).
        stalled_mixture = true;
        decay = std::exp(-m.stall_rate * span);
        const double ratio = m.stall_duration / span;
        const double f = ratio < 1.0 ? ratio : 1.0;
        Term moving = ll;
        moving.value += std::log1p(-p);
        moving.g[kP] -= 1.0 / (1.0 - p);
        moving.h(kP, kP) -= 1.0 / ((1.0 - p) * (1.0 - p));
        Term stalled;
        const std::array<double, 2> t{pm.x.v, pm.y.v};
        for (int c = 0; c < 2; ++c) {
          add_component(stalled, component_density(r[c] + f * t[c], v[c], student), kPx + c, kVx + c, -(1.0 - f), t[c],
                        1.0);
        }
        add_component(stalled, component_density(r[2], v[2], student), kPtheta, kVtheta, -1, 0, 0);
        stalled.value += std::log(p);
        stalled.g[kP] += 1.0 / p;
        stalled.h(kP, kP) -= 1.0 / (p * p);
        ll = log_sum_exp(moving, stalled);
        jac.add(kP, i_rate, span * decay);
        if (ratio < 1.0) jac.add(kF, i_duration, 1.0 / span);
      }
    }
    // Into the fields: ∇ += Jᵀ∇_u, ∇² += Jᵀ∇²_u J + Σ_a ∂ℓ/∂u_a ∇²u_a.
    total += ll.value;
    for (int a = 0; a < kInner; ++a) {
      for (int x = 0; x < jac.size[a]; ++x) g[jac.rows[a][x].first] += ll.g[a] * jac.rows[a][x].second;
    }
    for (int a = 0; a < kInner; ++a) {
      for (int e = 0; e < kInner; ++e) {
        const double hae = ll.h(a, e);
        if (hae == 0.0) continue;
        for (int x = 0; x < jac.size[a]; ++x) {
          const auto [i, ja] = jac.rows[a][x];
          for (int y = 0; y < jac.size[e]; ++y) h(i, jac.rows[e][y].first) += hae * ja * jac.rows[e][y].second;
        }
      }
    }
    if (ref) {
      const std::array<const Mean*, 3> pose{&pm.x, &pm.y, &pm.theta};
      for (int c = 0; c < 3; ++c) {
        if (pose[c]->n == 0) continue;
        for (int q = 0; q < nm; ++q) {
          for (int e = 0; e < nm; ++e) h(mean.to_full[q], mean.to_full[e]) += ll.g[kPx + c] * pose[c]->hessian(q, e);
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      if (i_sigma[c] >= 0) h(i_sigma[c], i_sigma[c]) += ll.g[kVx + c] * 2.0;
    }
    if (stalled_mixture && i_rate >= 0) h(i_rate, i_rate) -= ll.g[kP] * span * span * decay;
  }
  gradient = -g;
  hessian = -h;
  return -total;
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
  if (chain_rule_applies(d, fields)) {
    return chain_rule_pass(d, m, index, fields, mean, predicted, references, stalls, gradient, hessian);
  }
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
