#include "algorithms/diagnosis/compass_channel.h"

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/motion_windows.h"
#include "core/angle.h"
#include "core/chi_square.h"
#include "core/statistics.h"
#include "core/units.h"

#include <fmt/format.h>

#include <functional>
#include <map>
#include <optional>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/ml_fit.h"
#include "algorithms/diagnosis/selection.h"

namespace locbench::diagnosis {

std::vector<CompassResidual> compass_residuals(const CompassData& d, double time_offset) {
  std::vector<CompassResidual> out(d.readings.size());
  TruthInterpolator truth(d.truth);
  for (std::size_t i = 0; i < d.readings.size(); ++i) {
    const double t = d.readings[i].t - time_offset;
    const auto a = truth.at(t - 0.05), p = truth.at(t), b = truth.at(t + 0.05);
    if (!p) continue;
    out[i].t = d.readings[i].t;
    out[i].r = angle_diff(d.readings[i].heading, p->theta);
    out[i].x = p->x;
    out[i].y = p->y;
    out[i].turn_rate = a && b ? angle_diff(b->theta, a->theta) / 0.1 : 0.0;
    out[i].valid = true;
  }
  return out;
}

namespace {

double log_density(double e, double step, double sigma) {
  if (step <= 0.0) return -0.5 * (e * e / (sigma * sigma)) - std::log(sigma * std::sqrt(2.0 * kPi));
  const double hi = (e + 0.5 * step) / sigma, lo = (e - 0.5 * step) / sigma;
  // Φ(hi) − Φ(lo) through the upper tails for accuracy far from 0.
  const double mass =
      lo > 0.0 ? normal_upper_tail(lo) - normal_upper_tail(hi) : normal_upper_tail(-hi) - normal_upper_tail(-lo);
  return std::log(std::max(mass, 1e-300) / step);
}

bool in_zone(const CompassZone& z, double x, double y) { return z.enabled && std::hypot(x - z.x, y - z.y) <= z.radius; }

}  // namespace

double compass_nll(const CompassData& d, const CompassModel& m, const std::vector<std::size_t>& index) {
  const auto res = compass_residuals(d, m.time_offset);
  double nll = 0.0;
  const std::size_t n = index.empty() ? res.size() : index.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto& c = res[index.empty() ? k : index[k]];
    if (!c.valid) {
      nll -= log_density(0.0, m.step, m.sigma);
      continue;
    }
    const double e = wrap_angle(c.r - m.bias - (in_zone(m.zone, c.x, c.y) ? m.zone.bias : 0.0));
    nll -= log_density(e, m.step, m.sigma);
  }
  return nll;
}

CompassZone best_compass_zone(const CompassData& d, const CompassModel& m, const std::vector<std::size_t>& index) {
  const auto res = compass_residuals(d, m.time_offset);
  std::vector<const CompassResidual*> use;
  for (std::size_t k : index) {
    if (res[k].valid) use.push_back(&res[k]);
  }
  CompassZone best;
  double best_gain = 0.0;
  std::size_t searched = 0;
  const double var = m.sigma * m.sigma + m.step * m.step / 12.0;
  const std::size_t stride = std::max<std::size_t>(1, use.size() / 150);
  for (std::size_t c = 0; c < use.size(); c += stride) {
    for (double radius : {0.25, 0.5, 1.0, 2.0, 4.0}) {
      double sum = 0.0;
      std::size_t inside = 0;
      for (const auto* u : use) {
        if (std::hypot(u->x - use[c]->x, u->y - use[c]->y) <= radius) {
          sum += wrap_angle(u->r - m.bias);
          ++inside;
        }
      }
      if (inside < 10 || use.size() - inside < 10) continue;
      ++searched;
      const double gain = sum * sum / (2.0 * var * static_cast<double>(inside));  // Gaussian ΔNLL
      if (gain > best_gain) {
        best_gain = gain;
        best = {true, use[c]->x, use[c]->y, radius, sum / static_cast<double>(inside), 0};
      }
    }
  }
  best.candidates = searched;
  return best;
}

}  // namespace locbench::diagnosis

// ---------------------------------------------------------------- the channel
namespace locbench::diagnosis {
namespace {

// The causes the channel selects among, in catalog order.
const std::vector<std::string_view>& compass_candidates() {
  static const std::vector<std::string_view> ids{cause::kCompassBias, cause::kTimeOffset, cause::kCompassDisturbance};
  return ids;
}

struct CompassFit {
  CompassModel model;
  FitResult fit;  // σ, then bias and zone bias when free
  OffsetProfile offset;
  bool has_offset = false;
  double nll = 0.0;
  std::optional<Estimate> estimate(std::string_view id) const {
    if (id == cause::kTimeOffset) {
      if (!has_offset) return std::nullopt;
      return Estimate{"offset_s", offset.value, offset.lo, offset.hi};
    }
    const std::string name = id == cause::kCompassBias ? "bias_rad" : "max_bias_rad";
    for (std::size_t i = 0; i < fit.names.size(); ++i) {
      if (fit.names[i] == name) return Estimate{name, fit.values[i], fit.ci_low[i], fit.ci_high[i]};
    }
    return std::nullopt;
  }
};

class CompassFitter {
 public:
  CompassFitter(const CompassData& d, std::vector<std::size_t> index, double dt)
      : d_(d), index_(std::move(index)), dt_(dt) {}
  double nll(const CompassModel& m) const { return compass_nll(d_, m, index_); }

  // Newton on σ, bias and zone bias; a free offset profiled with the others held, alternating,
  // then its interval with the others re-fitted (selection.h).
  CompassFit fit(const std::vector<std::string_view>& free, CompassModel m) const {
    const bool offset = std::find(free.begin(), free.end(), cause::kTimeOffset) != free.end();
    CompassFit f = newton(free, m, 100);
    if (!offset) return f;
    for (int round = 0; round < 4; ++round) {
      const CompassModel held = f.model;
      const auto prof = profile_offset([&](double o) { return at_offset(held, o); }, {}, dt_);
      const double moved = std::abs(prof.value - held.time_offset);
      m = held;
      m.time_offset = prof.value;
      f = newton(free, m, 100);
      if (moved < 0.5 * prof.step) break;
    }
    const CompassModel best = f.model;
    f.offset = profile_offset([&](double o) { return at_offset(best, o); },
                              [&](double o) {
                                CompassModel x = best;
                                x.time_offset = o;
                                return newton(free, x, 15).nll;
                              },
                              dt_);
    f.model.time_offset = f.offset.value;
    f.has_offset = true;
    f.nll = nll(f.model);
    return f;
  }

 private:
  double at_offset(CompassModel m, double o) const {
    m.time_offset = o;
    return nll(m);
  }
  CompassFit newton(const std::vector<std::string_view>& free, const CompassModel& m, int iterations) const {
    std::vector<FitParameter> fp{{"sigma", m.sigma, 0.0, true}};
    for (const auto& id : free) {
      if (id == cause::kCompassBias) fp.push_back({"bias_rad", m.bias, 1e-3, false});
      if (id == cause::kCompassDisturbance) fp.push_back({"max_bias_rad", m.zone.bias, 1e-3, false});
    }
    auto apply = [&](const std::vector<double>& v) {
      CompassModel c = m;
      c.sigma = v[0];
      for (std::size_t i = 1; i < v.size(); ++i) {
        if (fp[i].name == "bias_rad") c.bias = v[i];
        if (fp[i].name == "max_bias_rad") c.zone.bias = v[i];
      }
      return c;
    };
    CompassFit f;
    f.fit = fit_max_likelihood([&](const std::vector<double>& v) { return nll(apply(v)); }, fp, iterations);
    for (const auto& p : fp) f.fit.names.push_back(p.name);
    f.model = apply(f.fit.values);
    f.nll = f.fit.nll;
    return f;
  }
  const CompassData& d_;
  std::vector<std::size_t> index_;
  double dt_;
};

}  // namespace

ChannelResult diagnose_compass(const MotionData& md, const DiagnosisOptions& opt) {
  ChannelResult out;
  CompassData d;
  d.readings = md.compass;
  d.truth = md.truth;
  d.declared_step = md.compass_step;
  std::vector<std::size_t> train, test;
  split_windows(d.readings.size(), opt.block, train, test);
  const auto res = compass_residuals(d, 0.0);
  std::vector<double> r, x, y, w, readings;
  for (std::size_t k : train) {
    if (!res[k].valid) continue;
    r.push_back(res[k].r);
    x.push_back(res[k].x);
    y.push_back(res[k].y);
    w.push_back(res[k].turn_rate);
  }
  for (const auto& c : d.readings) readings.push_back(c.heading);
  if (r.size() < 40) return out;
  const double dt = md.reference_interval;
  const CompassFitter fitter(d, train, dt);
  const double n_test = static_cast<double>(std::max<std::size_t>(test.size(), 1));
  auto heldout = [&](const CompassModel& before, const CompassModel& after) {
    return Gain{"heldout_nll_per_reading", compass_nll(d, before, test) / n_test, compass_nll(d, after, test) / n_test};
  };

  CompassModel declared;
  declared.step = d.declared_step;
  declared.sigma = std::max(sample_stddev(r), 1e-4);
  const CompassFit nominal = fitter.fit({}, declared);

  std::vector<double> rs = r;
  for (auto& v : rs) v /= nominal.model.sigma;
  out.tests.push_back(bias_test(rs, "compass"));
  out.tests.push_back(dependence_test(rs, x, "position_dependence", "compass", "x"));
  out.tests.push_back(dependence_test(rs, y, "position_dependence", "compass", "y"));
  out.tests.push_back(dependence_test(rs, w, "lead_lag", "compass", "turn rate"));
  out.tests.push_back(heavy_tail_test(rs, "compass"));
  const auto lat = find_lattice(readings);
  const bool coarser = lat && lat->step > d.declared_step * 1.01 + 1e-9;
  ResidualTest lt{"quantization_lattice", "compass_readings", "", "lattice_fraction"};
  lt.value = lat ? lat->on_lattice_fraction : 0.0;
  lt.strength = lat ? lat->step : 0.0;
  lt.p_value = coarser ? std::pow(2e-3, static_cast<double>(lat->n) * lat->on_lattice_fraction) : 1.0;
  out.tests.push_back(lt);

  // Quantization first (a lattice is exact evidence), then the likelihood causes.
  CompassFit base = nominal;
  {
    Cause c{std::string(cause::kCompassQuantization), "compass", coarser};
    c.statistic = "lattice_fraction";
    c.value = lt.value;
    c.threshold = 0.99;
    if (coarser) {
      c.parameters.push_back(
          {"step_rad", lat->step, lat->step - lat->step_uncertainty, lat->step + lat->step_uncertainty});
      c.parameters.push_back(
          {"offset_rad", lat->offset, lat->offset - lat->step_uncertainty, lat->offset + lat->step_uncertainty});
      CompassModel with = declared;
      with.step = lat->step;
      with.sigma = std::max(
          1e-4, std::sqrt(std::max(0.0, nominal.model.sigma * nominal.model.sigma - lat->step * lat->step / 12.0)));
      base = fitter.fit({}, with);
      c.gains.push_back(heldout(nominal.model, base.model));
    }
    c.explanation = explain(c);
    out.causes.push_back(c);
  }
  const auto& ids = compass_candidates();
  std::map<std::vector<std::size_t>, CompassFit> fits;
  std::map<std::size_t, std::size_t> discs;  // disc scans: candidates searched
  std::function<const CompassFit&(std::vector<std::size_t>)> fit_set =
      [&](std::vector<std::size_t> active) -> const CompassFit& {
    if (active.empty()) return base;
    std::vector<std::size_t> key = active;
    std::sort(key.begin(), key.end());
    if (auto it = fits.find(key); it != fits.end()) return it->second;
    CompassModel start = fit_set(std::vector<std::size_t>(active.begin(), active.end() - 1)).model;
    std::vector<std::string_view> free;
    for (std::size_t i : key) free.push_back(ids[i]);
    if (ids[active.back()] == cause::kCompassDisturbance) {
      start.zone = best_compass_zone(d, start, train);
      discs[active.back()] = std::max<std::size_t>(start.zone.candidates, 1);
      if (!start.zone.enabled) return fits[key] = CompassFit{start, {}, {}, false, fit_set({}).nll};
    }
    return fits[key] = fitter.fit(free, start);
  };
  const Selection sel = forward_select(
      ids.size(), base.nll,
      [&](std::size_t i) {
        // The disc is the best of those searched: its bias is judged at the level divided over them.
        const double scan =
            ids[i] == cause::kCompassDisturbance && discs.count(i) ? static_cast<double>(discs[i]) : 1.0;
        return chi_square_upper_quantile(ChiSquareDof(1.0), opt.false_alarm / (static_cast<double>(ids.size()) * scan));
      },
      [&](const std::vector<std::size_t>& active) {
        const CompassFit& f = fit_set(active);
        bool admissible = true;
        if (ids[active.back()] == cause::kTimeOffset) admissible = offset_resolved(f.model.time_offset);
        if (ids[active.back()] == cause::kCompassDisturbance) admissible = f.model.zone.enabled;
        return SelectionFit{f.nll, admissible};
      });
  const CompassFit& full = fit_set(sel.entered);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const bool entered = std::find(sel.entered.begin(), sel.entered.end(), i) != sel.entered.end();
    Cause c{std::string(ids[i]), "compass", entered};
    c.value = sel.evidence[i].lr;
    c.threshold = sel.evidence[i].threshold;
    const CompassFit& f = entered ? full : fit_set({i});
    if (auto e = f.estimate(ids[i])) c.parameters.push_back(*e);
    if (ids[i] == cause::kTimeOffset) c.extra["sensor"] = "compass";
    if (ids[i] == cause::kCompassDisturbance && f.model.zone.enabled) {
      c.extra["region"] = {
          {"shape", "disc"}, {"center_m", {f.model.zone.x, f.model.zone.y}}, {"radius_m", f.model.zone.radius}};
    }
    if (entered) {
      std::vector<std::size_t> others;
      for (std::size_t j : sel.entered) {
        if (j != i) others.push_back(j);
      }
      c.gains.push_back(heldout(fit_set(others).model, full.model));
      c.validated = c.gains.front().relative() > 0.0;
      c.detected = *c.validated;
      if (!c.detected) {
        out.heldout_notes.emplace_back(
            c.id, fmt::format("{} passed the likelihood ratio (LR {:.1f} ≥ {:.1f}) but did not "
                              "improve the held-out readings ({:.4g} → {:.4g})",
                              c.id, c.value, c.threshold, c.gains.front().before, c.gains.front().after));
      }
    }
    c.explanation = explain(c);
    out.causes.push_back(c);
  }
  std::stable_sort(out.causes.begin(), out.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.detected > b.detected; });
  std::vector<std::size_t> kept;
  for (std::size_t i : sel.entered) {
    for (const auto& c : out.causes) {
      if (c.id == ids[i] && c.detected) kept.push_back(i);
    }
  }
  const CompassFit& final_fit = fit_set(kept);
  if (coarser || !kept.empty()) out.overall_gain.push_back(heldout(nominal.model, final_fit.model));

  // What remains after the kept causes.
  const CompassModel& cm = final_fit.model;
  const auto fr = compass_residuals(d, cm.time_offset);
  std::vector<double> rr, fx, fy, fw;
  for (std::size_t k : train) {
    if (!fr[k].valid) continue;
    const bool in = cm.zone.enabled && std::hypot(fr[k].x - cm.zone.x, fr[k].y - cm.zone.y) <= cm.zone.radius;
    rr.push_back(wrap_angle(fr[k].r - cm.bias - (in ? cm.zone.bias : 0.0)) / std::max(cm.sigma, 1e-9));
    fx.push_back(fr[k].x);
    fy.push_back(fr[k].y);
    fw.push_back(fr[k].turn_rate);
  }
  out.remaining.push_back(bias_test(rr, "compass"));
  out.remaining.push_back(dependence_test(rr, fx, "position_dependence", "compass", "x"));
  out.remaining.push_back(dependence_test(rr, fy, "position_dependence", "compass", "y"));
  // A kept lattice accounts for the moment tests its round-off disturbs (cause_catalog.cpp).
  if (coarser) {
    std::erase_if(out.remaining,
                  [](const ResidualTest& t) { return accounts_for(cause_spec(cause::kCompassQuantization), t); });
  }
  // Lead/lag only when the best offset is beyond the resolution (see the odometry channel).
  if (offset_resolved(fit_set({1}).model.time_offset)) {
    out.remaining.push_back(dependence_test(rr, fw, "lead_lag", "compass", "turn rate"));
  }
  return out;
}

}  // namespace locbench::diagnosis
