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
  for_each_truth_sample(d.truth, d.readings, time_offset, [&](std::size_t i, const TruthSample& s) {
    out[i].t = d.readings[i].t;
    out[i].r = angle_diff(d.readings[i].heading, s.pose.theta);
    out[i].x = s.pose.x;
    out[i].y = s.pose.y;
    out[i].turn_rate = s.turn_rate;
    out[i].valid = true;
  });
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
  CompassFit fit(const std::vector<std::string_view>& free, const CompassModel& m) const {
    const bool offset = std::find(free.begin(), free.end(), cause::kTimeOffset) != free.end();
    if (!offset) return newton(free, m, 100);
    return fit_with_offset_profile<CompassFit>(
        m, [&](const CompassModel& x) { return newton(free, x, 100); },
        [&](const CompassModel& x) { return newton(free, x, 15).nll; }, [&](const CompassModel& x) { return nll(x); },
        dt_, 1);
  }

 private:
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
    adopt_fit(f, fit_max_likelihood([&](const std::vector<double>& v) { return nll(apply(v)); }, fp, iterations),
              apply);
    for (const auto& p : fp) f.fit.names.push_back(p.name);
    return f;
  }
  const CompassData& d_;
  std::vector<std::size_t> index_;
  double dt_;
};

// The compass data of a motion log, with its readings split into training and held-out ones.
struct CompassSplit {
  CompassData d;
  std::vector<std::size_t> train, test;
};

CompassSplit split_compass_data(const MotionData& md, std::size_t block) {
  CompassSplit s;
  s.d.readings = md.compass;
  s.d.truth = md.truth;
  s.d.declared_step = md.compass_step;
  split_windows(s.d.readings.size(), block, s.train, s.test);
  return s;
}

// Residuals of the training readings, with where they were taken and the turn rate there.
struct ResidualColumns {
  std::vector<double> r, x, y, turn_rate;
};

// Raw residuals at zero offset (bias and zone not removed).
ResidualColumns raw_training_residuals(const CompassSplit& s) {
  const auto res = compass_residuals(s.d, 0.0);
  ResidualColumns c;
  for (std::size_t k : s.train) {
    if (!res[k].valid) continue;
    c.r.push_back(res[k].r);
    c.x.push_back(res[k].x);
    c.y.push_back(res[k].y);
    c.turn_rate.push_back(res[k].turn_rate);
  }
  return c;
}

// Residuals left by a model, standardized by its σ.
ResidualColumns standardized_training_residuals(const CompassSplit& s, const CompassModel& cm) {
  const auto fr = compass_residuals(s.d, cm.time_offset);
  ResidualColumns c;
  for (std::size_t k : s.train) {
    if (!fr[k].valid) continue;
    const bool in = cm.zone.enabled && std::hypot(fr[k].x - cm.zone.x, fr[k].y - cm.zone.y) <= cm.zone.radius;
    c.r.push_back(wrap_angle(fr[k].r - cm.bias - (in ? cm.zone.bias : 0.0)) / std::max(cm.sigma, 1e-9));
    c.x.push_back(fr[k].x);
    c.y.push_back(fr[k].y);
    c.turn_rate.push_back(fr[k].turn_rate);
  }
  return c;
}

// Predictive likelihood per held-out reading, before and after.
Gain heldout_gain(const CompassSplit& s, const CompassModel& before, const CompassModel& after) {
  const double n_test = static_cast<double>(std::max<std::size_t>(s.test.size(), 1));
  return Gain{"heldout_nll_per_reading", compass_nll(s.d, before, s.test) / n_test,
              compass_nll(s.d, after, s.test) / n_test};
}

// The battery on the nominal model's standardized residuals.
std::vector<ResidualTest> nominal_battery(const ResidualColumns& raw, double sigma) {
  std::vector<double> rs = raw.r;
  for (auto& v : rs) v /= sigma;
  std::vector<ResidualTest> tests;
  tests.push_back(bias_test(rs, "compass"));
  tests.push_back(dependence_test(rs, raw.x, "position_dependence", "compass", "x"));
  tests.push_back(dependence_test(rs, raw.y, "position_dependence", "compass", "y"));
  tests.push_back(dependence_test(rs, raw.turn_rate, "lead_lag", "compass", "turn rate"));
  tests.push_back(heavy_tail_test(rs, "compass"));
  return tests;
}

// The printed readings' lattice, when coarser than the declared step.
struct ReadingLattice {
  std::optional<Lattice> lattice;
  bool coarser = false;
  ResidualTest test;
};

ReadingLattice reading_lattice(const CompassData& d) {
  std::vector<double> readings;
  for (const auto& c : d.readings) readings.push_back(c.heading);
  ReadingLattice out;
  out.lattice = find_lattice(readings);
  const auto& lat = out.lattice;
  out.coarser = lat && lat->step > d.declared_step * 1.01 + 1e-9;
  ResidualTest lt{"quantization_lattice", "compass_readings", "", "lattice_fraction"};
  lt.value = lat ? lat->on_lattice_fraction : 0.0;
  lt.strength = lat ? lat->step : 0.0;
  lt.p_value = out.coarser ? std::pow(2e-3, static_cast<double>(lat->n) * lat->on_lattice_fraction) : 1.0;
  out.test = lt;
  return out;
}

// The quantization cause, and the fit the likelihood causes start from: the nominal one, or
// with the lattice's step when the lattice is coarser than declared.
struct QuantizationFit {
  Cause cause;
  CompassFit base;
};

QuantizationFit fit_quantization(const ReadingLattice& rl, const CompassFit& nominal, const CompassModel& declared,
                                 const CompassFitter& fitter, const CompassSplit& s) {
  QuantizationFit out{{std::string(cause::kCompassQuantization), "compass", rl.coarser}, nominal};
  Cause& c = out.cause;
  const auto& lat = rl.lattice;
  c.statistic = "lattice_fraction";
  c.value = rl.test.value;
  c.threshold = 0.99;
  if (rl.coarser) {
    c.parameters.push_back(
        {"step_rad", lat->step, lat->step - lat->step_uncertainty, lat->step + lat->step_uncertainty});
    c.parameters.push_back(
        {"offset_rad", lat->offset, lat->offset - lat->step_uncertainty, lat->offset + lat->step_uncertainty});
    CompassModel with = declared;
    with.step = lat->step;
    with.sigma = std::max(
        1e-4, std::sqrt(std::max(0.0, nominal.model.sigma * nominal.model.sigma - lat->step * lat->step / 12.0)));
    out.base = fitter.fit({}, with);
    c.gains.push_back(heldout_gain(s, nominal.model, out.base.model));
  }
  c.explanation = explain(c);
  return out;
}

// Fits by active set (indices into compass_candidates()), each started from the fit of the set
// without its last member; the disturbance's disc searched first, and the number of discs searched
// kept for its threshold.
class CompassFitsBySet {
 public:
  CompassFitsBySet(const CompassFitter& fitter, const CompassSplit& s, CompassFit base)
      : fitter_(fitter), s_(s), base_(std::move(base)) {}

  const CompassFit& operator()(const std::vector<std::size_t>& active) {
    const auto& ids = compass_candidates();
    if (active.empty()) return base_;
    std::vector<std::size_t> key = active;
    std::sort(key.begin(), key.end());
    if (auto it = fits_.find(key); it != fits_.end()) return it->second;
    CompassModel start = (*this)(std::vector<std::size_t>(active.begin(), active.end() - 1)).model;
    std::vector<std::string_view> free;
    for (std::size_t i : key) free.push_back(ids[i]);
    if (ids[active.back()] == cause::kCompassDisturbance) {
      start.zone = best_compass_zone(s_.d, start, s_.train);
      discs_[active.back()] = std::max<std::size_t>(start.zone.candidates, 1);
      if (!start.zone.enabled) return fits_[key] = CompassFit{start, {}, {}, false, (*this)({}).nll};
    }
    return fits_[key] = fitter_.fit(free, start);
  }

  // How many discs were searched for candidate i (1 when it is not the disturbance or not yet fitted).
  double discs_searched(std::size_t i) const {
    const auto it = discs_.find(i);
    return compass_candidates()[i] == cause::kCompassDisturbance && it != discs_.end() ? static_cast<double>(it->second)
                                                                                       : 1.0;
  }

 private:
  const CompassFitter& fitter_;
  const CompassSplit& s_;
  CompassFit base_;
  std::map<std::vector<std::size_t>, CompassFit> fits_;
  std::map<std::size_t, std::size_t> discs_;  // disc scans: candidates searched
};

Selection select_compass_causes(CompassFitsBySet& fit_set, double false_alarm) {
  const auto& ids = compass_candidates();
  return forward_select(
      ids.size(), fit_set({}).nll,
      [&](std::size_t i) {
        // The disc is the best of those searched: its bias is judged at the level divided over them.
        const double scan = fit_set.discs_searched(i);
        return chi_square_upper_quantile(ChiSquareDof(1.0), false_alarm / (static_cast<double>(ids.size()) * scan));
      },
      [&](const std::vector<std::size_t>& active) {
        const CompassFit& f = fit_set(active);
        bool admissible = true;
        if (ids[active.back()] == cause::kTimeOffset) admissible = offset_resolved(f.model.time_offset);
        if (ids[active.back()] == cause::kCompassDisturbance) admissible = f.model.zone.enabled;
        return SelectionFit{f.nll, admissible};
      });
}

// Every candidate as a cause, with its estimate; one that entered is validated by its held-out
// gain (drop-one), and says so in a note when it fails.
struct DescribedCauses {
  std::vector<Cause> causes;
  std::vector<std::pair<std::string, std::string>> heldout_notes;
};

DescribedCauses describe_compass_causes(const Selection& sel, CompassFitsBySet& fit_set, const CompassSplit& s) {
  const auto& ids = compass_candidates();
  DescribedCauses out;
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
      c.gains.push_back(heldout_gain(s, fit_set(others).model, full.model));
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
  return out;
}

// The entered causes that were detected, in order of entry.
std::vector<std::size_t> kept_causes(const Selection& sel, const std::vector<Cause>& causes) {
  const auto& ids = compass_candidates();
  std::vector<std::size_t> kept;
  for (std::size_t i : sel.entered) {
    for (const auto& c : causes) {
      if (c.id == ids[i] && c.detected) kept.push_back(i);
    }
  }
  return kept;
}

// The battery on what remains after the kept causes.
std::vector<ResidualTest> remaining_battery(const ResidualColumns& rest, bool lattice_kept,
                                            bool offset_resolved_alone) {
  std::vector<ResidualTest> remaining;
  remaining.push_back(bias_test(rest.r, "compass"));
  remaining.push_back(dependence_test(rest.r, rest.x, "position_dependence", "compass", "x"));
  remaining.push_back(dependence_test(rest.r, rest.y, "position_dependence", "compass", "y"));
  // A kept lattice accounts for the moment tests its round-off disturbs (cause_catalog.cpp).
  if (lattice_kept) {
    std::erase_if(remaining,
                  [](const ResidualTest& t) { return accounts_for(cause_spec(cause::kCompassQuantization), t); });
  }
  // Lead/lag only when the best offset is beyond the resolution (see the odometry channel).
  if (offset_resolved_alone) {
    remaining.push_back(dependence_test(rest.r, rest.turn_rate, "lead_lag", "compass", "turn rate"));
  }
  return remaining;
}

}  // namespace

ChannelResult diagnose_compass(const MotionData& md, const DiagnosisOptions& opt) {
  ChannelResult out;
  const CompassSplit s = split_compass_data(md, opt.block);
  const ResidualColumns raw = raw_training_residuals(s);
  if (raw.r.size() < 40) return out;
  const CompassFitter fitter(s.d, s.train, md.reference_interval);
  CompassModel declared;
  declared.step = s.d.declared_step;
  declared.sigma = std::max(sample_stddev(raw.r), 1e-4);
  const CompassFit nominal = fitter.fit({}, declared);
  out.tests = nominal_battery(raw, nominal.model.sigma);
  const ReadingLattice rl = reading_lattice(s.d);
  out.tests.push_back(rl.test);

  // Quantization first (a lattice is exact evidence), then the likelihood causes.
  QuantizationFit quantization = fit_quantization(rl, nominal, declared, fitter, s);
  out.causes.push_back(quantization.cause);
  CompassFitsBySet fit_set(fitter, s, std::move(quantization.base));
  const Selection sel = select_compass_causes(fit_set, opt.false_alarm);
  DescribedCauses described = describe_compass_causes(sel, fit_set, s);
  out.causes.insert(out.causes.end(), described.causes.begin(), described.causes.end());
  out.heldout_notes = std::move(described.heldout_notes);
  std::stable_sort(out.causes.begin(), out.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.detected > b.detected; });
  const std::vector<std::size_t> kept = kept_causes(sel, out.causes);
  const CompassFit& final_fit = fit_set(kept);
  if (rl.coarser || !kept.empty()) out.overall_gain.push_back(heldout_gain(s, nominal.model, final_fit.model));
  out.remaining = remaining_battery(standardized_training_residuals(s, final_fit.model), rl.coarser,
                                    offset_resolved(fit_set({1}).model.time_offset));
  return out;
}

}  // namespace locbench::diagnosis
