#include "algorithms/diagnosis/odometry_channel.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/ml_fit.h"
#include "algorithms/diagnosis/odometry_battery.h"
#include "algorithms/diagnosis/odometry_derivatives.h"
#include "algorithms/diagnosis/selection.h"
#include "core/chi_square.h"
#include "core/statistics.h"

namespace locbench::diagnosis {

void split_windows(std::size_t n, std::size_t block, std::vector<std::size_t>& train, std::vector<std::size_t>& test) {
  for (std::size_t i = 0; i < n; ++i) ((i / block) % 3 == 2 ? test : train).push_back(i);
}

namespace {

using Field = double OdometryModel::*;

// One fit of the odometry model: the noise floor σ plus the parameters of the active causes by
// maximum likelihood; a time offset among them profiled (selection.h) over the others.
struct OdoFit {
  OdometryModel model;
  FitResult fit;
  std::vector<std::pair<std::string, Field>> coords;  // the fitted coordinates, in fit order
  bool has_offset = false;
  OffsetProfile offset;
  double nll = 0.0;

  std::optional<Estimate> estimate(const CauseParameter& p) const {
    if (p.field == &OdometryModel::time_offset) {
      if (!has_offset) return std::nullopt;
      return Estimate{p.name, offset.value, offset.lo, offset.hi};
    }
    for (std::size_t i = 0; i < coords.size(); ++i) {
      if (coords[i].second == p.field) return Estimate{p.name, fit.values[i], fit.ci_low[i], fit.ci_high[i]};
    }
    return std::nullopt;
  }
};

bool plausible(const OdometryModel& m) {
  return m.slip_loss >= -1.0 && m.slip_loss <= 1.0 && m.E_b > 0.1 && m.E_o > 0.1 && m.velocity_scale > 0.05 &&
         m.turn_rate_scale > 0.05 && m.drive_tau <= 2.0 && m.dof <= 1e4;
}

// A fit that puts a cause's parameter outside its plausible range (cause_catalog.h) is not
// evidence for the cause: on real logs a two-parameter cause can trade its parameters against
// each other (a speed-dependent scale of 1.9 at rest, −14 s/m) to absorb a different effect.
std::optional<std::string> implausible(const CauseSpec& spec, const OdometryModel& m) {
  for (const auto& p : spec.params) {
    if (p.field == nullptr || !(p.plausible_lo < p.plausible_hi)) continue;
    const double v = m.*(p.field);
    if (v < p.plausible_lo || v > p.plausible_hi) {
      return fmt::format("{} fits {} = {:.4g}{}, outside its plausible range [{:.4g}, {:.4g}]: not evidence for it",
                         spec.id, p.name, v, p.unit == "1" ? "" : " " + p.unit, p.plausible_lo, p.plausible_hi);
    }
  }
  return std::nullopt;
}

class Fitter {
 public:
  Fitter(const MotionData& d, std::vector<std::size_t> index, bool exact_derivatives)
      : d_(d), index_(std::move(index)), exact_(exact_derivatives), cache_(d) {}

  double nll(const OdometryModel& m) const { return negative_log_likelihood(d_, m, index_, &cache_); }

  // `interval`: profile the offset's 95% interval (costly: a fit per profile point); selection
  // needs only the likelihood, the report the interval.
  OdoFit fit(const std::vector<const CauseSpec*>& active, const OdometryModel& start, bool interval,
             int max_iterations = 100) const {
    const bool offset =
        std::any_of(active.begin(), active.end(), [](const CauseSpec* c) { return c->id == cause::kTimeOffset; });
    if (!offset) return fit_held_offset(active, start, max_iterations);
    std::function<double(const OdometryModel&)> refit;
    if (interval) refit = [&](const OdometryModel& m) { return fit_held_offset(active, m, 15).nll; };
    // At least two profiles before the offset counts as settled.
    return fit_with_offset_profile<OdoFit>(
        start, [&](const OdometryModel& m) { return fit_held_offset(active, m, max_iterations); }, refit,
        [&](const OdometryModel& m) { return nll(m); }, d_.reference_interval, 2);
  }

 private:
  OdoFit fit_held_offset(const std::vector<const CauseSpec*>& active, const OdometryModel& start,
                         int max_iterations) const {
    OdoFit out;
    std::vector<FitParameter> fp;
    auto add = [&](const std::string& name, Field field, double initial, double scale, bool positive) {
      for (const auto& c : out.coords) {
        if (c.second == field) return;
      }
      out.coords.emplace_back(name, field);
      fp.push_back({name, initial, scale, positive});
    };
    if (d_.reference != ReferenceKind::kCompass) {
      add("sigma_x", &OdometryModel::sigma_x, start.sigma_x, 0.0, true);
      add("sigma_y", &OdometryModel::sigma_y, start.sigma_y, 0.0, true);
    }
    add("sigma_theta", &OdometryModel::sigma_theta, start.sigma_theta, 0.0, true);
    const OdometryModel defaults;
    for (const CauseSpec* c : active) {
      for (const auto& p : c->params) {
        if (p.field == nullptr || p.field == &OdometryModel::time_offset) continue;
        const double initial = start.*(p.field) != defaults.*(p.field) ? start.*(p.field) : p.initial;
        add(p.name, p.field, initial, p.scale, p.positive);
      }
    }
    auto apply = [&](const std::vector<double>& v) {
      OdometryModel m;
      m.time_offset = start.time_offset;
      for (std::size_t i = 0; i < v.size(); ++i) m.*(out.coords[i].second) = v[i];
      return m;
    };
    std::vector<Field> fields;
    for (std::size_t i = 0; i < fp.size(); ++i) fields.push_back(out.coords[i].second);
    NllDerivatives derivatives;
    if (exact_) {
      derivatives = [&](const std::vector<double>& v, Eigen::VectorXd& g, Eigen::MatrixXd& h) {
        const OdometryModel m = apply(v);
        return plausible(m) && negative_log_likelihood_derivatives(d_, m, index_, fields, g, h, &cache_).has_value();
      };
    }
    adopt_fit(out,
              fit_max_likelihood(
                  [&](const std::vector<double>& v) {
                    const OdometryModel m = apply(v);
                    return plausible(m) ? nll(m) : std::numeric_limits<double>::infinity();
                  },
                  fp, max_iterations, derivatives),
              apply);
    return out;
  }

  const MotionData& d_;
  std::vector<std::size_t> index_;
  bool exact_;
  mutable WindowCache cache_;
};

OdometryModel initial_noise(const MotionData& d, const std::vector<std::size_t>& index) {
  OdometryModel m;
  std::vector<double> rx, ry, rt;
  for (std::size_t k : index) {
    const auto r = window_residual(d, d.windows[k], m);
    if (!r.valid) continue;
    rx.push_back(r.r[0]);
    ry.push_back(r.r[1]);
    rt.push_back(r.r[2]);
  }
  auto sd = [](const std::vector<double>& v) { return v.size() > 1 ? std::max(rms(v), 1e-6) : 1e-3; };
  m.sigma_x = sd(rx);
  m.sigma_y = sd(ry);
  m.sigma_theta = sd(rt);
  return m;
}

// ---------------------------------------------------------------- held-out gains
struct HeldOut {
  Gain translation, heading, likelihood;
};

HeldOut heldout(const MotionData& d, const OdometryModel& before, const OdometryModel& after,
                const std::vector<std::size_t>& test, std::size_t chain) {
  const double n = static_cast<double>(std::max<std::size_t>(test.size(), 1));
  const auto rb = relative_pose_error(d, before, test, chain), ra = relative_pose_error(d, after, test, chain);
  return {{"heldout_translation_error_m", rb.translation_rms, ra.translation_rms},
          {"heldout_heading_error_rad", rb.heading_rms, ra.heading_rms},
          {"heldout_nll_per_window", negative_log_likelihood(d, before, test) / n,
           negative_log_likelihood(d, after, test) / n}};
}

// The cause's primary metric first (cause_catalog.h), then the others.
std::vector<Gain> ordered_gains(const HeldOut& h, PrimaryMetric metric, bool heading_only) {
  PrimaryMetric m = metric;
  if (heading_only && (m == PrimaryMetric::kTranslation || m == PrimaryMetric::kTranslationOrHeading)) {
    m = PrimaryMetric::kHeading;
  }
  if (m == PrimaryMetric::kTranslationOrHeading) {
    m = h.translation.relative() >= h.heading.relative() ? PrimaryMetric::kTranslation : PrimaryMetric::kHeading;
  }
  switch (m) {
    case PrimaryMetric::kTranslation: return {h.translation, h.heading, h.likelihood};
    case PrimaryMetric::kHeading:
      return heading_only ? std::vector<Gain>{h.heading, h.likelihood}
                          : std::vector<Gain>{h.heading, h.translation, h.likelihood};
    default:
      return heading_only ? std::vector<Gain>{h.likelihood, h.heading}
                          : std::vector<Gain>{h.likelihood, h.translation, h.heading};
  }
}

std::string format_estimate(const Estimate& e) { return fmt::format("{:.4g} [{:.4g}, {:.4g}]", e.value, e.lo, e.hi); }

void encoder_lattice(const MotionData& d, const OdometryModel& nominal_fit, const std::vector<std::size_t>& test,
                     std::size_t chain, OdometryChannelResult& out) {
  std::vector<std::int64_t> inc;
  for (const auto& s : d.steps) {
    inc.push_back(static_cast<std::int64_t>(s.a));
    inc.push_back(static_cast<std::int64_t>(s.b));
  }
  const auto lat = find_integer_lattice(inc);
  ResidualTest lt{"quantization_lattice", "encoder_increments", "", "lattice_fraction"};
  lt.value = lat ? lat->on_lattice_fraction : 0.0;
  lt.strength = lat ? lat->step : 1.0;
  lt.p_value = lat ? std::pow(1.0 / lat->step, static_cast<double>(lat->n) * lat->on_lattice_fraction) : 1.0;
  out.tests.push_back(lt);
  Cause cause{std::string(cause::kEncoderQuantization), "odometry", lat.has_value()};
  cause.statistic = "lattice_fraction";
  cause.value = lt.value;
  cause.threshold = 0.99;
  if (lat) {
    const double c = 0.5 * (d.nominal.meters_per_tick_left + d.nominal.meters_per_tick_right);
    const double s = lat->step * c;
    cause.parameters.push_back({"step_m", s, s, s});
    cause.extra["step_ticks"] = lat->step;
    // Gain: the residual floor the lattice implies (step²/6 per wheel per window) against the
    // declared tick's, as predictive likelihood on held-out windows.
    OdometryModel with = nominal_fit;
    with.sigma_x = std::max(with.sigma_x, std::sqrt(s * s / 12.0));
    with.sigma_theta = std::max(with.sigma_theta, std::sqrt(s * s / 3.0) / d.nominal.wheelbase);
    cause.gains = ordered_gains(heldout(d, nominal_fit, with, test, chain), PrimaryMetric::kLikelihood, false);
    cause.explanation = explain(cause);
  }
  out.causes.push_back(cause);
}

// ---------------------------------------------------------------- fits by active set
// Fits by active set (sorted indices into the candidates), each started from the fit of the set
// without its last member when there is one; `reported` the same with the offset's interval
// profiled, for the fits the report shows.
class OdoFitsBySet {
 public:
  OdoFitsBySet(const Fitter& fitter, const std::vector<const CauseSpec*>& candidates, const OdoFit& nominal)
      : fitter_(fitter), candidates_(candidates), nominal_(nominal) {}

  const OdoFit& operator()(const std::vector<std::size_t>& active) {
    if (active.empty()) return nominal_;
    std::vector<std::size_t> key = active;
    std::sort(key.begin(), key.end());
    if (auto it = fits_.find(key); it != fits_.end()) return it->second;
    std::vector<std::size_t> without(active.begin(), active.end() - 1);
    const OdometryModel start = start_of(active, (*this)(without).model);
    return fits_[key] = fitter_.fit(specs(key), start, false);
  }

  // The start of `active`'s fit: the fit without its last member, with that member's parameters
  // where it was fitted alone, when it was (nearer the optimum than the catalog's initial values:
  // fewer Newton steps). Not a time offset: fitted alone it takes up the drive's lag, and its
  // profile started there stays on that side of the lag–offset ridge.
  OdometryModel start_of(const std::vector<std::size_t>& active, OdometryModel start) const {
    if (active.size() < 2 || candidates_[active.back()]->id == cause::kTimeOffset) return start;
    const auto alone = fits_.find({active.back()});
    if (alone == fits_.end()) return start;
    for (const auto& p : candidates_[active.back()]->params) {
      if (p.field != nullptr) start.*(p.field) = alone->second.model.*(p.field);
    }
    return start;
  }

  // The fits of `sets` not fitted yet, side by side (each from the fit without its last member,
  // those fitted first, side by side, the same way), each with its own copy of the fitter's window
  // cache: the same fits on any number of threads.
  void prefit(const std::vector<std::vector<std::size_t>>& sets) {
    std::vector<FitJob> jobs;
    RoundSets starts;
    for (const auto& active : sets) {
      if (active.empty()) continue;
      std::vector<std::size_t> key = active;
      std::sort(key.begin(), key.end());
      const bool queued = std::any_of(jobs.begin(), jobs.end(), [&](const FitJob& j) { return j.key == key; });
      if (fits_.count(key) != 0 || queued) continue;
      jobs.push_back({key, {}, active.back()});
      starts.emplace_back(active.begin(), active.end() - 1);
    }
    if (jobs.empty()) return;
    prefit(starts);
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      std::vector<std::size_t> active = starts[i];
      active.push_back(jobs[i].last);
      jobs[i].start = start_of(active, (*this)(starts[i]).model);
    }
    fit_side_by_side(jobs, false, fits_);
  }

  // The fits of `sets` not fitted yet, side by side, each started from `start` (a fit of a larger
  // set: the causes a set lacks are nominal in its fit, a time offset it lacks set to 0).
  void prefit_from(const RoundSets& sets, const OdometryModel& start) {
    std::vector<FitJob> jobs;
    for (const auto& active : sets) {
      std::vector<std::size_t> key = active;
      std::sort(key.begin(), key.end());
      const bool queued = std::any_of(jobs.begin(), jobs.end(), [&](const FitJob& j) { return j.key == key; });
      if (key.empty() || fits_.count(key) != 0 || queued) continue;
      OdometryModel from = start;
      if (!has_offset(key)) from.time_offset = 0.0;
      jobs.push_back({key, from, key.back()});
    }
    fit_side_by_side(jobs, false, fits_);
  }

  const OdoFit& reported(std::vector<std::size_t> active) {
    std::sort(active.begin(), active.end());
    if (!has_offset(active)) return (*this)(active);
    if (auto it = reported_.find(active); it != reported_.end()) return it->second;
    return reported_[active] = fitter_.fit(specs(active), (*this)(active).model, true);
  }

  // The reported fits of `sets` (those with a profiled offset interval, not made yet) side by
  // side, as `prefit` does for the plain ones.
  void prefit_reported(RoundSets sets) {
    std::vector<FitJob> jobs;
    for (auto& active : sets) {
      std::sort(active.begin(), active.end());
      const bool queued = std::any_of(jobs.begin(), jobs.end(), [&](const FitJob& j) { return j.key == active; });
      if (!has_offset(active) || reported_.count(active) != 0 || queued) continue;
      jobs.push_back({active, (*this)(active).model});
    }
    fit_side_by_side(jobs, true, reported_);
  }

  // A fit to make: the sorted active set and its start.
  struct FitJob {
    std::vector<std::size_t> key;
    OdometryModel start;
    std::size_t last = 0;  // the member added last (prefit)
  };

  // The fits of `jobs` in parallel, each with its own copy of the fitter's window cache, entered
  // into `into` in the order of `jobs`.
  void fit_side_by_side(const std::vector<FitJob>& jobs, bool interval,
                        std::map<std::vector<std::size_t>, OdoFit>& into) const {
    std::vector<OdoFit> fitted(jobs.size());
    tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t i) {
      const Fitter own = fitter_;
      fitted[i] = own.fit(specs(jobs[i].key), jobs[i].start, interval);
    });
    for (std::size_t i = 0; i < jobs.size(); ++i) into.emplace(jobs[i].key, std::move(fitted[i]));
  }

  bool has_offset(const std::vector<std::size_t>& active) const {
    return std::any_of(active.begin(), active.end(),
                       [&](std::size_t i) { return candidates_[i]->id == cause::kTimeOffset; });
  }

  std::vector<const CauseSpec*> specs(const std::vector<std::size_t>& active) const {
    std::vector<const CauseSpec*> out;
    for (std::size_t i : active) out.push_back(candidates_[i]);
    return out;
  }

 private:
  const Fitter& fitter_;
  const std::vector<const CauseSpec*>& candidates_;
  const OdoFit& nominal_;
  std::map<std::vector<std::size_t>, OdoFit> fits_, reported_;
};

// ---------------------------------------------------------------- selection
struct OdometrySelection {
  Selection sel;
  std::map<std::size_t, std::string> implausible_notes;  // the last implausible fit of a candidate
};

// Forward selection of the specific causes, then of the generic ones given those (a specific
// cause that explains a symptom is named before a generic model of the symptom).
OdometrySelection select_odometry_causes(OdoFitsBySet& fit_set, const std::vector<const CauseSpec*>& candidates,
                                         double false_alarm) {
  const double m = static_cast<double>(candidates.size());
  auto threshold = [&](std::size_t i) {
    return chi_square_upper_quantile(ChiSquareDof(static_cast<double>(candidates[i]->params.size())), false_alarm / m);
  };
  OdometrySelection out;
  Selection& sel = out.sel;
  sel.evidence.resize(candidates.size());
  for (const bool generic : {false, true}) {
    std::vector<std::size_t> pool;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (candidates[i]->generic == generic) pool.push_back(i);
    }
    const std::vector<std::size_t> before = sel.entered;
    const Selection phase = forward_select(
        pool.size(), fit_set(before).nll, [&](std::size_t k) { return threshold(pool[k]); },
        [&](const std::vector<std::size_t>& active) {
          std::vector<std::size_t> all = before;
          for (std::size_t k : active) all.push_back(pool[k]);
          const OdoFit& f = fit_set(all);
          const CauseSpec& last = *candidates[all.back()];
          const bool offset = last.id == cause::kTimeOffset;
          if (const auto why = implausible(last, f.model)) {
            out.implausible_notes[all.back()] = *why;
            return SelectionFit{f.nll, false};
          }
          return SelectionFit{f.nll, !offset || offset_resolved(f.model.time_offset)};
        },
        [&](const RoundSets& round) {
          RoundSets sets;
          for (const auto& active : round) {
            sets.push_back(before);
            for (std::size_t k : active) sets.back().push_back(pool[k]);
          }
          fit_set.prefit(sets);
        });
    for (std::size_t k : phase.entered) sel.entered.push_back(pool[k]);
    for (std::size_t k = 0; k < pool.size(); ++k) sel.evidence[pool[k]] = phase.evidence[k];
  }
  return out;
}

// ---------------------------------------------------------------- held-out check
struct HeldOutCheck {
  std::vector<std::size_t> kept;                                          // the causes that earned their place
  std::map<std::size_t, std::vector<Gain>> gains;                         // per cause, in its own metric first
  std::vector<std::pair<std::size_t, std::vector<std::size_t>>> dropped;  // cause, the set it was judged in
};

// The held-out check, per cause in its own metric: the model with the other causes against the
// same model without this one (drop-one), both fitted on the training windows. Backward
// elimination: two causes that act alike (a velocity scale and drive stalls both shorten the
// mean distance) each look useless beside the other, so the worst cause without a gain is
// dropped and the rest are judged again, until every remaining cause earns its place.
HeldOutCheck eliminate_causes_without_gain(const MotionData& d, OdoFitsBySet& fit_set,
                                           const std::vector<const CauseSpec*>& candidates,
                                           const std::vector<std::size_t>& entered,
                                           const std::vector<std::size_t>& test, std::size_t chain, bool heading_only) {
  HeldOutCheck out;
  std::vector<std::size_t>& kept = out.kept;
  kept = entered;
  while (!kept.empty()) {
    const OdoFit& full = fit_set(kept);
    RoundSets drop_one;
    for (std::size_t i : kept) {
      drop_one.emplace_back();
      for (std::size_t j : kept) {
        if (j != i) drop_one.back().push_back(j);
      }
    }
    // Each drop-one set from the full fit, the dropped cause nominal (not from a chain of its
    // prefixes, which selection never fitted).
    fit_set.prefit_from(drop_one, full.model);
    std::optional<std::size_t> worst;
    for (std::size_t i : kept) {
      std::vector<std::size_t> others;
      for (std::size_t j : kept) {
        if (j != i) others.push_back(j);
      }
      auto& g = out.gains[i];
      g = ordered_gains(heldout(d, fit_set(others).model, full.model, test, chain), candidates[i]->metric,
                        heading_only);
      if (g.front().relative() <= 0.0 && (!worst || g.front().relative() < out.gains[*worst].front().relative())) {
        worst = i;
      }
    }
    if (!worst) break;
    out.dropped.emplace_back(*worst, kept);
    std::erase(kept, *worst);
  }
  return out;
}

// Why a cause that passed the likelihood ratio was dropped: do the halves of the log agree on the
// cause's parameter?
std::string dropped_cause_note(const MotionData& d, OdoFitsBySet& fit_set, const CauseSpec& spec,
                               const std::vector<std::size_t>& judged_in, const std::vector<std::size_t>& train,
                               const Evidence& evidence, const Gain& g, bool exact_derivatives) {
  const OdoFit& full = fit_set(judged_in);
  const auto& p = spec.params.front();
  std::vector<std::size_t> first(train.begin(), train.begin() + static_cast<long>(train.size() / 2));
  std::vector<std::size_t> second(train.begin() + static_cast<long>(train.size() / 2), train.end());
  const std::vector<const CauseSpec*> specs = fit_set.specs(judged_in);
  std::optional<Estimate> a, b;
  tbb::parallel_invoke([&] { a = Fitter(d, first, exact_derivatives).fit(specs, full.model, false).estimate(p); },
                       [&] { b = Fitter(d, second, exact_derivatives).fit(specs, full.model, false).estimate(p); });
  std::string note = fmt::format(
      "{} passed the likelihood ratio (LR {:.1f} ≥ {:.1f}) but did not reduce the held-out {} "
      "({:.4g} → {:.4g})",
      spec.id, evidence.lr, evidence.threshold, g.metric, g.before, g.after);
  if (a && b && a->lo < a->hi && b->lo < b->hi && (a->hi < b->lo || b->hi < a->lo)) {
    note += fmt::format(": non-stationary, the halves of the log disagree on {}: {} vs {}", p.name, format_estimate(*a),
                        format_estimate(*b));
  }
  return note;
}

// ---------------------------------------------------------------- causes
Cause describe_cause(const MotionData& d, const CauseSpec& spec, const Evidence& evidence, const OdoFit& f,
                     bool detected, bool heading_only) {
  Cause c{std::string(spec.id), "odometry", detected};
  c.value = evidence.lr;
  c.threshold = evidence.threshold;
  for (const auto& p : spec.params) {
    if (auto e = f.estimate(p)) c.parameters.push_back(*e);
  }
  if (spec.id == cause::kTimeOffset) c.extra["sensor"] = heading_only ? "odometry_vs_compass" : "odometry";
  if (spec.id == cause::kDriveStall) c.extra["mean_distance_scale"] = mean_distance_scale(d, f.model);
  return c;
}

// Every candidate as a cause: the entered ones first, in order of entry, with their held-out
// gains (the kept ones at the final fit), then the others at their fit alone.
std::vector<Cause> describe_causes(const MotionData& d, OdoFitsBySet& fit_set,
                                   const std::vector<const CauseSpec*>& candidates, const Selection& sel,
                                   const HeldOutCheck& check, const OdoFit& final_fit, bool heading_only) {
  std::vector<Cause> causes;
  for (std::size_t i : sel.entered) {
    const bool keep = std::find(check.kept.begin(), check.kept.end(), i) != check.kept.end();
    Cause c = describe_cause(d, *candidates[i], sel.evidence[i], keep ? final_fit : fit_set.reported(sel.entered), keep,
                             heading_only);
    c.validated = keep;
    c.gains = check.gains.at(i);
    causes.push_back(c);
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (std::find(sel.entered.begin(), sel.entered.end(), i) != sel.entered.end()) continue;
    const OdoFit& alone = candidates[i]->id == cause::kTimeOffset ? fit_set.reported({i}) : fit_set({i});
    causes.push_back(describe_cause(d, *candidates[i], sel.evidence[i], alone, false, heading_only));
  }
  return causes;
}

// Confounding: a kept cause whose estimate is (almost) perfectly correlated with another
// candidate's that also explains the data alone cannot be told apart from it by these data. The
// causes of a group are marked not identifiable.
std::vector<ConfoundedGroup> confounded_groups(OdoFitsBySet& fit_set, const std::vector<const CauseSpec*>& candidates,
                                               const std::vector<std::size_t>& kept, double nominal_nll,
                                               double false_alarm, std::vector<Cause>& causes) {
  const double m = static_cast<double>(candidates.size());
  // The pairs fitted together: a kept one-parameter cause with another that passes alone.
  const auto paired = [&](std::size_t a, std::size_t c) {
    const CauseSpec &sa = *candidates[a], &sc = *candidates[c];
    if (c == a || sc.noise || sa.noise || sc.params.size() != 1 || sa.params.size() != 1) return false;
    return 2.0 * (nominal_nll - fit_set({c}).nll) > chi_square_upper_quantile(ChiSquareDof(1.0), false_alarm / m);
  };
  RoundSets pairs;
  for (std::size_t a : kept) {
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (paired(a, c)) pairs.push_back({a, c});
    }
  }
  fit_set.prefit(pairs);
  std::vector<ConfoundedGroup> confounded;
  for (std::size_t a : kept) {
    const CauseSpec& sa = *candidates[a];
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const CauseSpec& sc = *candidates[c];
      if (!paired(a, c)) continue;
      const OdoFit& both = fit_set({a, c});
      if (both.fit.max_abs_correlation < 0.98) continue;
      const bool seen = std::any_of(confounded.begin(), confounded.end(), [&](const ConfoundedGroup& g) {
        return std::find(g.ids.begin(), g.ids.end(), std::string(sc.id)) != g.ids.end();
      });
      if (seen) continue;
      const std::string pa = sa.params[0].name, pc = sc.params[0].name;
      const auto ea = fit_set({a}).estimate(sa.params[0]);
      if (!ea) continue;
      const bool ratio = (pa == "E_b" && pc == "E_o") || (pa == "E_o" && pc == "E_b");
      ConfoundedGroup g;
      g.ids = {std::string(sa.id), std::string(sc.id)};
      g.combination = fmt::format("{} = {:.6g} [{:.6g}, {:.6g}] (correlation {:.4f} when fitted together)",
                                  ratio ? pa + "/" + pc : pa + " with " + pc + " nominal", ea->value, ea->lo, ea->hi,
                                  both.fit.max_abs_correlation);
      g.explanation = fmt::format(
          "{} and {} act on these residuals the same way (the reference has no independent "
          "distance or turn measurement that separates them); only their combination is determined",
          sa.id, sc.id);
      confounded.push_back(g);
      for (auto& cause : causes) {
        if (cause.id == sa.id || cause.id == sc.id) cause.identifiable = false;
      }
    }
  }
  return confounded;
}

// What remains after the kept causes. A kept noise cause accounts for the shape tests it names
// (standardized residuals stay heavy-tailed under a Student-t or slip model by design). Lead/lag
// is the signature of a time offset; an offset within the resolution is neither a cause nor
// structure.
std::vector<ResidualTest> remaining_battery(const MotionData& d, OdoFitsBySet& fit_set,
                                            const std::vector<const CauseSpec*>& candidates,
                                            const std::vector<std::size_t>& kept, const OdometryModel& final_model,
                                            const std::vector<std::size_t>& train) {
  std::vector<ResidualTest> remaining = odometry_battery(d, odometry_residuals(d, final_model, train));
  for (std::size_t i : kept) {
    if (!candidates[i]->noise) continue;
    std::erase_if(remaining, [&](const ResidualTest& t) { return accounts_for(*candidates[i], t); });
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i]->id != cause::kTimeOffset) continue;
    if (!offset_resolved(fit_set({i}).model.time_offset)) {
      std::erase_if(remaining, [](const ResidualTest& t) { return t.name == "lead_lag"; });
    }
  }
  return remaining;
}

}  // namespace

OdometryChannelResult diagnose_odometry(const MotionData& d, const DiagnosisOptions& opt) {
  OdometryChannelResult out;
  std::vector<std::size_t> train, test;
  split_windows(d.windows.size(), opt.block, train, test);
  const bool heading_only = d.reference == ReferenceKind::kCompass;
  const auto candidates = odometry_causes(d);
  const Fitter fitter(d, train, opt.exact_derivatives);
  const OdoFit nominal = fitter.fit({}, initial_noise(d, train), false);
  out.nominal_fit = nominal.model;
  out.tests = odometry_battery(d, odometry_residuals(d, nominal.model, train));

  OdoFitsBySet fit_set(fitter, candidates, nominal);
  const OdometrySelection selection = select_odometry_causes(fit_set, candidates, opt.false_alarm);
  const Selection& sel = selection.sel;
  // A candidate that never entered because its fit left the plausible range says so: the
  // structure it would explain is then reported with that reason, not as "unexplained" alone.
  for (const auto& [i, why] : selection.implausible_notes) {
    if (std::find(sel.entered.begin(), sel.entered.end(), i) == sel.entered.end()) {
      out.heldout_notes.emplace_back(std::string(candidates[i]->id), why);
    }
  }
  const HeldOutCheck check =
      eliminate_causes_without_gain(d, fit_set, candidates, sel.entered, test, opt.rpe_chain, heading_only);
  // The fits the report shows with an offset interval (describe_causes): the kept set's, the
  // entered set's when a cause was dropped, an offset that did not enter alone.
  RoundSets shown{check.kept};
  if (check.kept.size() != sel.entered.size()) shown.push_back(sel.entered);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (std::find(sel.entered.begin(), sel.entered.end(), i) == sel.entered.end()) shown.push_back({i});
  }
  fit_set.prefit_reported(shown);
  for (const auto& [i, judged_in] : check.dropped) {
    out.heldout_notes.emplace_back(std::string(candidates[i]->id),
                                   dropped_cause_note(d, fit_set, *candidates[i], judged_in, train, sel.evidence[i],
                                                      check.gains.at(i).front(), opt.exact_derivatives));
  }
  const OdoFit& final_fit = fit_set.reported(check.kept);
  out.final_fit = final_fit.model;
  out.causes = describe_causes(d, fit_set, candidates, sel, check, final_fit, heading_only);
  out.confounded = confounded_groups(fit_set, candidates, check.kept, nominal.nll, opt.false_alarm, out.causes);
  for (auto& c : out.causes) c.explanation = explain(c);
  if (!check.kept.empty()) {
    const HeldOut h = heldout(d, nominal.model, final_fit.model, test, opt.rpe_chain);
    out.overall_gain = heading_only ? std::vector<Gain>{h.heading, h.likelihood}
                                    : std::vector<Gain>{h.translation, h.heading, h.likelihood};
  }
  if (d.odometry == OdometryKind::kEncoder) encoder_lattice(d, nominal.model, test, opt.rpe_chain, out);
  out.remaining = remaining_battery(d, fit_set, candidates, check.kept, final_fit.model, train);
  return out;
}

}  // namespace locbench::diagnosis
