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
  LmFitter(const LandmarkData& d, std::vector<std::size_t> index) : d_(d), index_(std::move(index)) {}

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
    LmFit f = newton(free, m, 100);
    if (!offset || hold_offset) return f;
    const double dt = d_.reference_interval;
    for (int round = 0; round < 4; ++round) {
      const LandmarkModel held = f.model;
      const auto prof = profile_offset([&](double o) { return at_offset(held, o); }, {}, dt);
      const double moved = std::abs(prof.value - held.time_offset);
      m = held;
      m.time_offset = prof.value;
      f = newton(free, m, 100);
      if (moved < 0.5 * prof.step) break;
    }
    const LandmarkModel best = f.model;
    std::function<double(double)> profiled;
    if (interval) {
      profiled = [&](double o) {
        LandmarkModel x = best;
        x.time_offset = o;
        return newton({}, x, 3).nll;  // σ_r, σ_b re-fitted (the offset trades against them)
      };
    }
    f.offset = profile_offset([&](double o) { return at_offset(best, o); }, profiled, dt);
    f.model.time_offset = f.offset.value;
    f.has_offset = true;
    f.nll = nll(f.model);
    return f;
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
  double at_offset(LandmarkModel m, double o) const {
    m.time_offset = o;
    return nll(m);
  }
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
    out.fit = fit_max_likelihood(
        [&](const std::vector<double>& v) {
          const LandmarkModel x = apply(v);
          return x.dof <= 1e4 ? landmark_nll(d_, g, x, index_) : std::numeric_limits<double>::infinity();
        },
        fp, iterations);
    for (const auto& p : fp) out.fit.names.push_back(p.name);
    out.model = apply(out.fit.values);
    out.nll = out.fit.nll;
    return out;
  }

  const LandmarkData& d_;
  std::vector<std::size_t> index_;
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

  const LmFitter fitter(d, train);
  LandmarkModel start;
  start.sigma_range = std::max(rms(rr), 1e-4);
  start.sigma_bearing = std::max(rms(rb), 1e-5);
  const LmFit nominal = fitter.fit({}, start, false);
  out.nominal_fit = nominal.model;
  out.tests = landmark_battery(d, g0, nominal.model, train);

  const auto candidates = landmark_causes();
  std::vector<std::size_t> sel_order;  // the candidates entered so far, in order
  // Selection fits, by the ordered list of candidates entered: each adds the last candidate's
  // parameters to the model of the list without it and fits them with σ_r, σ_b, holding the
  // parameters already in (a time offset, once profiled, among them). The likelihood ratio is
  // then that of the added cause at the others' earlier values — a little conservative — and a
  // fit costs a few parameters instead of all of them (MRCLAM: ~4000 observations per robot).
  std::map<std::vector<std::size_t>, LmFit> steps;
  std::size_t searched = 1;  // landmarks searched for the displaced one
  std::function<const LmFit&(const std::vector<std::size_t>&)> step_fit =
      [&](const std::vector<std::size_t>& active) -> const LmFit& {
    if (active.empty()) return nominal;
    if (auto it = steps.find(active); it != steps.end()) return it->second;
    LandmarkModel m = step_fit(std::vector<std::size_t>(active.begin(), active.end() - 1)).model;
    const CauseSpec* added = candidates[active.back()];
    if (added->id == cause::kLandmarkPositionError) {
      const LmDisplacement x = fitter.displaced(m);
      searched = std::max<std::size_t>(x.searched, 1);
      if (x.id < 0) return steps[active] = LmFit{m, {}, {}, {}, false, nominal.nll};
      m.position_error_id = x.id;
      m.position_error_dx = x.dx;
      m.position_error_dy = x.dy;
    }
    return steps[active] = fitter.fit({added}, m, false);
  };
  // Joint fits of a set of causes (every parameter free, started from the selection fit; a time
  // offset held there), and with `interval` the offset profiled again with its 95% interval.
  std::map<std::pair<std::vector<std::size_t>, bool>, LmFit> joints;
  auto joint_fit = [&](std::vector<std::size_t> set, bool interval) -> const LmFit& {
    std::vector<std::size_t> ordered;  // in order of entry when entered, else as given
    for (std::size_t i : sel_order) {
      if (std::find(set.begin(), set.end(), i) != set.end()) ordered.push_back(i);
    }
    for (std::size_t i : set) {
      if (std::find(ordered.begin(), ordered.end(), i) == ordered.end()) ordered.push_back(i);
    }
    std::sort(set.begin(), set.end());
    if (set.empty()) return nominal;
    if (auto it = joints.find({set, interval}); it != joints.end()) return it->second;
    std::vector<const CauseSpec*> specs;
    for (std::size_t i : set) specs.push_back(candidates[i]);
    const LmFit& entry_fit = step_fit(ordered);
    if (entry_fit.model.position_error_id < 0 && std::any_of(set.begin(), set.end(), [&](std::size_t i) {
          return candidates[i]->id == cause::kLandmarkPositionError;
        })) {
      return joints[{set, interval}] = entry_fit;
    }
    LmFit f = fitter.fit(specs, entry_fit.model, false, true);
    if (interval) f = fitter.fit(specs, f.model, true);
    return joints[{set, interval}] = f;
  };

  const double m = static_cast<double>(candidates.size());
  auto threshold = [&](std::size_t i) {
    const double scan = candidates[i]->id == cause::kLandmarkPositionError ? static_cast<double>(searched) : 1.0;
    return chi_square_upper_quantile(ChiSquareDof(static_cast<double>(candidates[i]->params.size())),
                                     opt.false_alarm / (m * scan));
  };
  // Specific causes first, then the generic heavy-tail model; once it has entered, the specific
  // causes are tried again under it (a range bias that outliers hide from the normal model shows
  // under the Student-t one), until a round adds nothing.
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
          pool.size(), step_fit(before).nll, [&](std::size_t k) { return threshold(pool[k]); },
          [&](const std::vector<std::size_t>& active) {
            std::vector<std::size_t> all = before;
            for (std::size_t k : active) all.push_back(pool[k]);
            const LmFit& f = step_fit(all);
            const CauseSpec& last = *candidates[all.back()];
            bool admissible = lm_plausible(last, f);
            if (last.id == cause::kLandmarkTimeOffset) admissible = admissible && offset_resolved(f.model.time_offset);
            if (last.id == cause::kLandmarkPositionError) admissible = admissible && f.model.position_error_id >= 0;
            return SelectionFit{f.nll, admissible};
          });
      for (std::size_t k : phase.entered) sel.entered.push_back(pool[k]);
      sel_order = sel.entered;
      for (std::size_t k = 0; k < pool.size(); ++k) sel.evidence[pool[k]] = phase.evidence[k];
    }
    if (sel.entered.size() == entered_before) break;
  }

  // The held-out check, drop-one: the full model against the same model without the cause (its
  // parameters back to nominal, σ_r and σ_b re-fitted on the training observations; the other
  // causes' parameters kept at their joint values — re-fitting them all costs several joint fits).
  const LmFit& full = joint_fit(sel.entered, true);
  auto without = [&](std::size_t i) {
    LandmarkModel reduced = full.model;
    const LandmarkModel nominal_values;
    const CauseSpec& spec = *candidates[i];
    for (std::size_t k = 0; k < spec.params.size(); ++k) {
      if (const LmField f = field_of(spec.id, k)) reduced.*f = nominal_values.*f;
    }
    if (spec.id == cause::kLandmarkTimeOffset) reduced.time_offset = 0.0;
    if (spec.id == cause::kLandmarkPositionError) reduced.position_error_id = -1;
    // σ_r may have gone to ~0 beside a range-dependent noise: start its re-fit from a usable value.
    reduced.sigma_range = std::max(reduced.sigma_range, 0.01);
    return fitter.fit({}, reduced, false).model;
  };
  std::vector<std::size_t> kept;
  std::map<std::size_t, std::vector<Gain>> gains;
  for (std::size_t i : sel.entered) {
    gains[i] = lm_heldout(fitter, d, without(i), full.model, test);
    if (gains[i].front().relative() > 0.0) {
      kept.push_back(i);
    } else {
      const Gain& g = gains[i].front();
      out.heldout_notes.emplace_back(
          std::string(candidates[i]->id),
          fmt::format("{} passed the likelihood ratio (LR {:.1f} ≥ {:.1f}) but did not improve the held-out "
                      "observations ({:.4g} → {:.4g})",
                      candidates[i]->id, sel.evidence[i].lr, sel.evidence[i].threshold, g.before, g.after));
    }
  }
  const LmFit& final_fit = joint_fit(kept, true);
  out.final_fit = final_fit.model;

  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const CauseSpec& spec = *candidates[i];
    const bool entered = std::find(sel.entered.begin(), sel.entered.end(), i) != sel.entered.end();
    const bool keep = std::find(kept.begin(), kept.end(), i) != kept.end();
    Cause c{std::string(spec.id), "landmark", keep};
    c.value = sel.evidence[i].lr;
    c.threshold = sel.evidence[i].threshold;
    const LmFit& f = keep ? final_fit : joint_fit(entered ? sel.entered : std::vector<std::size_t>{i}, true);
    for (std::size_t k = 0; k < spec.params.size(); ++k) {
      if (auto e = f.estimate(spec, k)) c.parameters.push_back(*e);
    }
    if (spec.id == cause::kLandmarkPositionError && f.model.position_error_id >= 0) {
      c.extra["landmark"] = f.model.position_error_id;
      c.extra["landmarks_searched"] = searched;
    }
    if (entered) {
      c.validated = keep;
      c.gains = gains[i];
    }
    c.explanation = explain(c);
    out.causes.push_back(c);
  }
  std::stable_sort(out.causes.begin(), out.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.detected > b.detected; });
  if (!kept.empty()) out.overall_gain = lm_heldout(fitter, d, nominal.model, final_fit.model, test);

  // What remains after the kept causes; a kept noise cause accounts for the shape tests it names.
  out.remaining = landmark_battery(d, fitter.geometry(final_fit.model.time_offset), final_fit.model, train);
  for (std::size_t i : kept) {
    if (!candidates[i]->noise) continue;
    std::erase_if(out.remaining, [&](const ResidualTest& t) { return accounts_for(*candidates[i], t); });
  }
  // Lead/lag only when the best offset alone is beyond the resolution (see the compass channel).
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i]->id == cause::kLandmarkTimeOffset && !offset_resolved(step_fit({i}).model.time_offset)) {
      std::erase_if(out.remaining, [](const ResidualTest& t) { return t.name == "lead_lag"; });
    }
  }
  return out;
}

}  // namespace locbench::diagnosis
