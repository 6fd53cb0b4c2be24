#include "algorithms/diagnosis/landmark_channel.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/landmark_battery.h"
#include "algorithms/diagnosis/landmark_derivatives.h"
#include "algorithms/diagnosis/ml_fit.h"
#include "algorithms/diagnosis/selection.h"
#include "core/angle.h"
#include "core/chi_square.h"
#include "core/statistics.h"

namespace locbench::diagnosis {

void split_by_time(const std::vector<LandmarkReading>& readings, double block_s, std::vector<std::size_t>& train,
                   std::vector<std::size_t>& test) {
  if (readings.empty()) return;
  const double t0 = readings.front().t;
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const auto block = static_cast<long long>(std::floor((readings[i].t - t0) / block_s));
    (block % 3 == 2 ? test : train).push_back(i);
  }
}

namespace {

using LmField = double LandmarkModel::*;

// The model field each catalog parameter sets (the time offset is profiled, not listed).
LmField field_of(std::string_view id, std::size_t k) {
  if (id == cause::kLandmarkRangeScale) return &LandmarkModel::range_scale;
  if (id == cause::kLandmarkRangeBias) return &LandmarkModel::range_bias;
  if (id == cause::kLandmarkRangeOffAxis)
    return k == 0 ? &LandmarkModel::range_off_axis_linear : &LandmarkModel::range_off_axis;
  if (id == cause::kLandmarkBearingBias) return &LandmarkModel::bearing_bias;
  if (id == cause::kLandmarkRangeNoise) return &LandmarkModel::range_noise_slope;
  if (id == cause::kLandmarkTurnNoise) return &LandmarkModel::bearing_noise_turn_slope;
  if (id == cause::kLandmarkHeavyTails) return &LandmarkModel::dof;
  if (id == cause::kLandmarkPositionError)
    return k == 0 ? &LandmarkModel::position_error_dx : &LandmarkModel::position_error_dy;
  return nullptr;
}

struct LmFit {
  LandmarkModel model;
  FitResult fit;
  std::vector<LmField> coords;  // the fitted coordinates, in fit order
  OffsetProfile offset;
  bool has_offset = false;
  double nll = 0.0;
  std::optional<Estimate> estimate(const CauseSpec& spec, std::size_t k) const {
    const std::string& name = spec.params[k].name;
    if (spec.id == cause::kLandmarkTimeOffset) {
      if (!has_offset) return std::nullopt;
      return Estimate{name, offset.value, offset.lo, offset.hi};
    }
    const LmField f = field_of(spec.id, k);
    for (std::size_t i = 0; i < coords.size(); ++i) {
      if (coords[i] == f) return Estimate{name, fit.values[i], fit.ci_low[i], fit.ci_high[i]};
    }
    return std::nullopt;
  }
};

// The displaced landmark: the one whose own observations gain most from moving it.
struct LmDisplacement {
  int id = -1;
  double dx = 0.0, dy = 0.0;
  std::size_t searched = 0;
};

class LmFitter {
 public:
  // `exact_derivatives`: the fits' Newton steps use landmark_derivatives.h (else central differences).
  LmFitter(const LandmarkData& d, std::vector<std::size_t> index, bool exact_derivatives)
      : d_(d), index_(std::move(index)), exact_(exact_derivatives) {}

  const std::vector<LandmarkGeometry>& geometry(double offset) const {
    if (auto it = geometry_.find(offset); it != geometry_.end()) return it->second;
    if (geometry_.size() > 256) geometry_.clear();
    return geometry_[offset] = landmark_geometry(d_, offset);
  }
  double nll(const LandmarkModel& m, const std::vector<std::size_t>& index) const {
    return landmark_nll(d_, geometry(m.time_offset), m, index);
  }
  double nll(const LandmarkModel& m) const { return nll(m, index_); }

  // A free offset alternates with the others: profiled (selection.h) with them held, then they
  // re-fitted, until it moves less than half a fine step; `interval`: its 95% interval from the
  // profile with σ_r, σ_b re-fitted at each offset. `hold_offset`: the offset stays at the start
  // model's value (joint fits started where it was profiled already).
  LmFit fit(const std::vector<const CauseSpec*>& free, LandmarkModel m, bool interval, bool hold_offset = false) const {
    const bool offset =
        std::any_of(free.begin(), free.end(), [](const CauseSpec* c) { return c->id == cause::kLandmarkTimeOffset; });
    if (!offset || hold_offset) return newton(free, m, 100);
    std::function<double(const LandmarkModel&)> refit;
    if (interval) {
      refit = [&](const LandmarkModel& x) {
        return newton({}, x, 3).nll;
      };  // σ_r, σ_b re-fitted (the offset trades against them)
    }
    return fit_with_offset_profile<LmFit>(
        m, [&](const LandmarkModel& x) { return newton(free, x, 100); }, refit,
        [&](const LandmarkModel& x) { return nll(x); }, d_.reference_interval, 1);
  }

  // Each landmark with ≥ 10 observations: (dx, dy) fitted on its own observations, the rest of
  // the model held; the largest likelihood gain wins.
  LmDisplacement displaced(const LandmarkModel& m) const {
    std::map<int, std::vector<std::size_t>> by;
    for (std::size_t i : index_) by[d_.landmark[i]].push_back(i);
    LmDisplacement best;
    double best_gain = 0.0;
    for (const auto& entry : by) {
      const int k = entry.first;
      const std::vector<std::size_t>& idx = entry.second;  // not a binding: clang 14 cannot capture those
      if (idx.size() < 10) continue;
      ++best.searched;
      LandmarkModel x = m;
      x.position_error_id = d_.map[static_cast<std::size_t>(k)].id;
      x.position_error_dx = x.position_error_dy = 0.0;
      const double before = nll(x, idx);
      const FitResult r = fit_max_likelihood(
          [&](const std::vector<double>& v) {
            LandmarkModel y = x;
            y.position_error_dx = v[0];
            y.position_error_dy = v[1];
            return nll(y, idx);
          },
          {{"dx_m", 0.0, 1e-2, false}, {"dy_m", 0.0, 1e-2, false}}, 30);
      if (before - r.nll > best_gain) {
        best_gain = before - r.nll;
        best.id = x.position_error_id;
        best.dx = r.values[0];
        best.dy = r.values[1];
      }
    }
    return best;
  }

 private:
  LmFit newton(const std::vector<const CauseSpec*>& free, const LandmarkModel& m, int iterations) const {
    LmFit out;
    // σ_r on a linear scale, used as |σ_r| (the variance holds σ_r²): beside a range-dependent
    // noise the data may put it at 0, where a log scale has no curvature and every interval of
    // the fit would be lost with the Hessian.
    std::vector<FitParameter> fp{{"sigma_range", m.sigma_range, 0.01, false},
                                 {"sigma_bearing", m.sigma_bearing, 0.0, true}};
    out.coords = {&LandmarkModel::sigma_range, &LandmarkModel::sigma_bearing};
    const LandmarkModel defaults;
    for (const CauseSpec* c : free) {
      for (std::size_t k = 0; k < c->params.size(); ++k) {
        const LmField f = field_of(c->id, k);
        if (f == nullptr) continue;
        const auto& p = c->params[k];
        const double initial = m.*f != defaults.*f ? m.*f : p.initial;
        out.coords.push_back(f);
        fp.push_back({p.name, initial, p.scale, p.positive});
      }
    }
    auto apply = [&](const std::vector<double>& v) {
      LandmarkModel x = m;
      for (std::size_t i = 0; i < v.size(); ++i) x.*(out.coords[i]) = v[i];
      x.sigma_range = std::abs(x.sigma_range);
      return x;
    };
    const auto& g = geometry(m.time_offset);
    NllDerivatives derivatives;
    if (exact_) {
      derivatives = [&](const std::vector<double>& v, Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
        const LandmarkModel x = apply(v);
        if (!(x.dof <= 1e4) || !landmark_nll_derivatives(d_, g, x, index_, out.coords, gradient, hessian)) return false;
        if (v[0] < 0.0) {  // σ_r = |v₀|
          gradient[0] = -gradient[0];
          hessian.row(0) *= -1.0;
          hessian.col(0) *= -1.0;
        }
        return true;
      };
    }
    const auto objective = [&](const std::vector<double>& v) {
      const LandmarkModel x = apply(v);
      return x.dof <= 1e4 ? landmark_nll(d_, g, x, index_) : std::numeric_limits<double>::infinity();
    };
    adopt_fit(out, fit_max_likelihood(objective, fp, iterations, derivatives), apply);
    for (const auto& p : fp) out.fit.names.push_back(p.name);
    return out;
  }

  const LandmarkData& d_;
  std::vector<std::size_t> index_;
  bool exact_;
  mutable std::map<double, std::vector<LandmarkGeometry>> geometry_;
};

// Held-out gains: predictive NLL per observation (primary), then the RMS range and bearing
// residuals of the model's mean.
std::vector<Gain> lm_heldout(const LmFitter& f, const LandmarkData& d, const LandmarkModel& before,
                             const LandmarkModel& after, const std::vector<std::size_t>& test) {
  const double n = static_cast<double>(std::max<std::size_t>(test.size(), 1));
  auto rms_of = [&](const LandmarkModel& m, bool range) {
    const auto& g = f.geometry(m.time_offset);
    std::vector<double> v;
    for (std::size_t i : test) {
      const auto r = landmark_residual(d, i, g[i], m);
      if (r.valid) v.push_back(range ? r.range : r.bearing);
    }
    return v.empty() ? 0.0 : rms(v);
  };
  return {{"heldout_nll_per_observation", f.nll(before, test) / n, f.nll(after, test) / n},
          {"heldout_range_rms_m", rms_of(before, true), rms_of(after, true)},
          {"heldout_bearing_rms_rad", rms_of(before, false), rms_of(after, false)}};
}

bool lm_plausible(const CauseSpec& spec, const LmFit& f) {
  for (std::size_t k = 0; k < spec.params.size(); ++k) {
    const auto& p = spec.params[k];
    const auto e = f.estimate(spec, k);
    if (e && p.plausible_lo < p.plausible_hi && (e->value < p.plausible_lo || e->value > p.plausible_hi)) return false;
  }
  return true;
}

// Selection fits, by the ordered list of candidates entered: each adds the last candidate's
// parameters to the model of the list without it and fits them with σ_r, σ_b, holding the
// parameters already in (a time offset, once profiled, among them). The likelihood ratio is
// then that of the added cause at the others' earlier values — a little conservative — and a
// fit costs a few parameters instead of all of them (MRCLAM: ~4000 observations per robot).
// Joint fits of a set of causes: every parameter free, started from the selection fit (a time
// offset held there), and with `interval` the offset profiled again with its 95% interval.
class LandmarkFits {
 public:
  LandmarkFits(const LmFitter& fitter, const std::vector<const CauseSpec*>& candidates, const LmFit& nominal)
      : fitter_(fitter), candidates_(candidates), nominal_(nominal) {}

  const LmFit& step(const std::vector<std::size_t>& active) {
    if (active.empty()) return nominal_;
    if (auto it = steps_.find(active); it != steps_.end()) return it->second;
    LandmarkModel m = step(std::vector<std::size_t>(active.begin(), active.end() - 1)).model;
    const CauseSpec* added = candidates_[active.back()];
    if (added->id == cause::kLandmarkPositionError) {
      const LmDisplacement x = fitter_.displaced(m);
      searched_ = std::max<std::size_t>(x.searched, 1);
      if (x.id < 0) return steps_[active] = LmFit{m, {}, {}, {}, false, nominal_.nll};
      m.position_error_id = x.id;
      m.position_error_dx = x.dx;
      m.position_error_dy = x.dy;
    }
    return steps_[active] = fitter_.fit({added}, m, false);
  }

  const LmFit& joint(std::vector<std::size_t> set, bool interval) {
    std::vector<std::size_t> ordered;  // in order of entry when entered, else as given
    for (std::size_t i : entry_order_) {
      if (std::find(set.begin(), set.end(), i) != set.end()) ordered.push_back(i);
    }
    for (std::size_t i : set) {
      if (std::find(ordered.begin(), ordered.end(), i) == ordered.end()) ordered.push_back(i);
    }
    std::sort(set.begin(), set.end());
    if (set.empty()) return nominal_;
    if (auto it = joints_.find({set, interval}); it != joints_.end()) return it->second;
    std::vector<const CauseSpec*> specs;
    for (std::size_t i : set) specs.push_back(candidates_[i]);
    const LmFit& entry_fit = step(ordered);
    if (entry_fit.model.position_error_id < 0 && std::any_of(set.begin(), set.end(), [&](std::size_t i) {
          return candidates_[i]->id == cause::kLandmarkPositionError;
        })) {
      return joints_[{set, interval}] = entry_fit;
    }
    LmFit f = fitter_.fit(specs, entry_fit.model, false, true);
    if (interval) f = fitter_.fit(specs, f.model, true);
    return joints_[{set, interval}] = f;
  }

  // The candidates entered so far, in order (joint fits start from their selection fit).
  void set_entry_order(const std::vector<std::size_t>& entered) { entry_order_ = entered; }
  // Landmarks searched for the displaced one.
  std::size_t searched() const { return searched_; }

 private:
  const LmFitter& fitter_;
  const std::vector<const CauseSpec*>& candidates_;
  const LmFit& nominal_;
  std::vector<std::size_t> entry_order_;
  std::map<std::vector<std::size_t>, LmFit> steps_;
  std::map<std::pair<std::vector<std::size_t>, bool>, LmFit> joints_;
  std::size_t searched_ = 1;
};

// Specific causes first, then the generic heavy-tail model; once it has entered, the specific
// causes are tried again under it (a range bias that outliers hide from the normal model shows
// under the Student-t one), until a round adds nothing.
Selection select_landmark_causes(LandmarkFits& fits, const std::vector<const CauseSpec*>& candidates,
                                 double false_alarm) {
  const double m = static_cast<double>(candidates.size());
  auto threshold = [&](std::size_t i) {
    const double scan = candidates[i]->id == cause::kLandmarkPositionError ? static_cast<double>(fits.searched()) : 1.0;
    return chi_square_upper_quantile(ChiSquareDof(static_cast<double>(candidates[i]->params.size())),
                                     false_alarm / (m * scan));
  };
  Selection sel;
  sel.evidence.resize(candidates.size());
  for (int round = 0; round < 3; ++round) {
    const std::size_t entered_before = sel.entered.size();
    for (const bool generic : {false, true}) {
      std::vector<std::size_t> pool;
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        const bool in = std::find(sel.entered.begin(), sel.entered.end(), i) != sel.entered.end();
        if (candidates[i]->generic == generic && !in) pool.push_back(i);
      }
      if (pool.empty()) continue;
      const std::vector<std::size_t> before = sel.entered;
      const Selection phase = forward_select(
          pool.size(), fits.step(before).nll, [&](std::size_t k) { return threshold(pool[k]); },
          [&](const std::vector<std::size_t>& active) {
            std::vector<std::size_t> all = before;
            for (std::size_t k : active) all.push_back(pool[k]);
            const LmFit& f = fits.step(all);
            const CauseSpec& last = *candidates[all.back()];
            bool admissible = lm_plausible(last, f);
            if (last.id == cause::kLandmarkTimeOffset) admissible = admissible && offset_resolved(f.model.time_offset);
            if (last.id == cause::kLandmarkPositionError) admissible = admissible && f.model.position_error_id >= 0;
            return SelectionFit{f.nll, admissible};
          });
      for (std::size_t k : phase.entered) sel.entered.push_back(pool[k]);
      fits.set_entry_order(sel.entered);
      for (std::size_t k = 0; k < pool.size(); ++k) sel.evidence[pool[k]] = phase.evidence[k];
    }
    if (sel.entered.size() == entered_before) break;
  }
  return sel;
}

// The full model without one cause: its parameters back to nominal, σ_r and σ_b re-fitted on
// the training observations; the other causes' parameters kept at their joint values (re-fitting
// them all costs several joint fits).
LandmarkModel without_cause(const LmFitter& fitter, const LandmarkModel& full, const CauseSpec& spec) {
  LandmarkModel reduced = full;
  const LandmarkModel nominal_values;
  for (std::size_t k = 0; k < spec.params.size(); ++k) {
    if (const LmField f = field_of(spec.id, k)) reduced.*f = nominal_values.*f;
  }
  if (spec.id == cause::kLandmarkTimeOffset) reduced.time_offset = 0.0;
  if (spec.id == cause::kLandmarkPositionError) reduced.position_error_id = -1;
  // σ_r may have gone to ~0 beside a range-dependent noise: start its re-fit from a usable value.
  reduced.sigma_range = std::max(reduced.sigma_range, 0.01);
  return fitter.fit({}, reduced, false).model;
}

struct LandmarkHeldOutCheck {
  std::vector<std::size_t> kept;
  std::map<std::size_t, std::vector<Gain>> gains;
  std::vector<std::pair<std::string, std::string>> notes;  // per cause that failed
};

// The held-out check, drop-one: the full model against the same model without the cause.
LandmarkHeldOutCheck landmark_heldout_check(const LmFitter& fitter, const LandmarkData& d, const LmFit& full,
                                            const std::vector<const CauseSpec*>& candidates, const Selection& sel,
                                            const std::vector<std::size_t>& test) {
  LandmarkHeldOutCheck out;
  for (std::size_t i : sel.entered) {
    out.gains[i] = lm_heldout(fitter, d, without_cause(fitter, full.model, *candidates[i]), full.model, test);
    if (out.gains[i].front().relative() > 0.0) {
      out.kept.push_back(i);
    } else {
      const Gain& g = out.gains[i].front();
      out.notes.emplace_back(
          std::string(candidates[i]->id),
          fmt::format("{} passed the likelihood ratio (LR {:.1f} ≥ {:.1f}) but did not improve the held-out "
                      "observations ({:.4g} → {:.4g})",
                      candidates[i]->id, sel.evidence[i].lr, sel.evidence[i].threshold, g.before, g.after));
    }
  }
  return out;
}

// Every candidate as a cause: a kept one at the final fit, an entered one at the joint fit of
// those entered, any other at its joint fit alone.
std::vector<Cause> describe_landmark_causes(LandmarkFits& fits, const std::vector<const CauseSpec*>& candidates,
                                            const Selection& sel, const LandmarkHeldOutCheck& check,
                                            const LmFit& final_fit) {
  std::vector<Cause> causes;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const CauseSpec& spec = *candidates[i];
    const bool entered = std::find(sel.entered.begin(), sel.entered.end(), i) != sel.entered.end();
    const bool keep = std::find(check.kept.begin(), check.kept.end(), i) != check.kept.end();
    Cause c{std::string(spec.id), "landmark", keep};
    c.value = sel.evidence[i].lr;
    c.threshold = sel.evidence[i].threshold;
    const LmFit& f = keep ? final_fit : fits.joint(entered ? sel.entered : std::vector<std::size_t>{i}, true);
    for (std::size_t k = 0; k < spec.params.size(); ++k) {
      if (auto e = f.estimate(spec, k)) c.parameters.push_back(*e);
    }
    if (spec.id == cause::kLandmarkPositionError && f.model.position_error_id >= 0) {
      c.extra["landmark"] = f.model.position_error_id;
      c.extra["landmarks_searched"] = fits.searched();
    }
    if (entered) {
      c.validated = keep;
      c.gains = check.gains.at(i);
    }
    c.explanation = explain(c);
    causes.push_back(c);
  }
  return causes;
}

// What remains after the kept causes; a kept noise cause accounts for the shape tests it names.
// Lead/lag only when the best offset alone is beyond the resolution (see the compass channel).
std::vector<ResidualTest> remaining_battery(const LandmarkData& d, const LmFitter& fitter, LandmarkFits& fits,
                                            const std::vector<const CauseSpec*>& candidates,
                                            const std::vector<std::size_t>& kept, const LmFit& final_fit,
                                            const std::vector<std::size_t>& train) {
  std::vector<ResidualTest> remaining =
      landmark_battery(d, fitter.geometry(final_fit.model.time_offset), final_fit.model, train);
  for (std::size_t i : kept) {
    if (!candidates[i]->noise) continue;
    std::erase_if(remaining, [&](const ResidualTest& t) { return accounts_for(*candidates[i], t); });
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i]->id == cause::kLandmarkTimeOffset && !offset_resolved(fits.step({i}).model.time_offset)) {
      std::erase_if(remaining, [](const ResidualTest& t) { return t.name == "lead_lag"; });
    }
  }
  return remaining;
}

}  // namespace

LandmarkChannelResult diagnose_landmarks(const LandmarkData& d, const DiagnosisOptions& opt) {
  LandmarkChannelResult out;
  out.unmapped = d.unmapped;
  std::vector<std::size_t> train, test;
  split_by_time(d.readings, static_cast<double>(opt.block) * opt.windows.duration, train, test);
  const auto g0 = landmark_geometry(d, 0.0);
  std::vector<double> rr, rb;
  for (std::size_t i : train) {
    if (!g0[i].valid) continue;
    rr.push_back(d.readings[i].range - g0[i].rho);
    rb.push_back(wrap_angle(d.readings[i].bearing - g0[i].phi));
  }
  for (const auto& g : g0) out.observations += g.valid ? 1 : 0;
  if (rr.size() < 40 || test.empty()) return out;
  out.testable = true;

  const LmFitter fitter(d, train, opt.exact_derivatives);
  LandmarkModel start;
  start.sigma_range = std::max(rms(rr), 1e-4);
  start.sigma_bearing = std::max(rms(rb), 1e-5);
  const LmFit nominal = fitter.fit({}, start, false);
  out.nominal_fit = nominal.model;
  out.tests = landmark_battery(d, g0, nominal.model, train);

  const auto candidates = landmark_causes();
  LandmarkFits fits(fitter, candidates, nominal);
  const Selection sel = select_landmark_causes(fits, candidates, opt.false_alarm);
  const LmFit& full = fits.joint(sel.entered, true);
  LandmarkHeldOutCheck check = landmark_heldout_check(fitter, d, full, candidates, sel, test);
  out.heldout_notes = std::move(check.notes);
  const LmFit& final_fit = fits.joint(check.kept, true);
  out.final_fit = final_fit.model;
  double widest = 0.0;
  for (const LandmarkReading& r : d.readings) widest = std::max(widest, std::abs(wrap_angle(r.bearing)));
  if (widest > 0.0) out.final_fit.field_of_view = widest;
  out.causes = describe_landmark_causes(fits, candidates, sel, check, final_fit);
  std::stable_sort(out.causes.begin(), out.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.detected > b.detected; });
  if (!check.kept.empty()) out.overall_gain = lm_heldout(fitter, d, nominal.model, final_fit.model, test);
  out.remaining = remaining_battery(d, fitter, fits, candidates, check.kept, final_fit, train);
  return out;
}

}  // namespace locbench::diagnosis
