#include "pipelines/diagnosis_plots.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/odometry_model.h"
#include "core/units.h"
#include "experiment_framework/plot_series.h"

namespace locbench::experiments {
namespace {

using diagnosis::Cause;
using diagnosis::MotionData;
using diagnosis::OdometryModel;

// The residual component and covariate that reveal a cause; empty component: noise causes (they
// change the spread, not the mean: the CDFs show them).
struct Revealing {
  int component = -1;  // 0 along-track [m], 2 heading [rad]
  std::string covariate;
};
Revealing revealing(const std::string& id) {
  namespace c = diagnosis::cause;
  if (id == c::kVelocityScale || id == c::kSpeedDependentScale || id == c::kDriveStall || id == c::kMeanDiameterScale ||
      id == c::kDriveResponse) {
    return {0, "speed"};
  }
  if (id == c::kTurnRateScale || id == c::kTurnRateBias || id == c::kWheelbaseScale) return {2, "turn_rate"};
  if (id == c::kWheelDiameterRatio) return {2, "signed_distance"};
  if (id == c::kTimeOffset) return {2, "turn_rate_change"};
  return {};
}

// Per window: the covariate named (NaN where undefined).
std::vector<double> covariate(const MotionData& d, const std::string& name) {
  const auto& w = d.windows;
  std::vector<double> rate(w.size()), out(w.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double T = w[i].t1 - w[i].t0;
    rate[i] = T > 0.0 ? (name == "speed" ? w[i].distance : w[i].turn) / T : std::numeric_limits<double>::quiet_NaN();
  }
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (name == "speed" || name == "turn_rate")
      out[i] = rate[i];
    else if (name == "signed_distance")
      out[i] = w[i].signed_distance;
    else if (name == "turn_rate_change" && i > 0 && i + 1 < w.size()) {
      const double T = w[i + 1].t0 - w[i - 1].t0;  // neighbours' turn rates, centred difference
      const double r0 = w[i - 1].turn / (w[i - 1].t1 - w[i - 1].t0), r1 = w[i + 1].turn / (w[i + 1].t1 - w[i + 1].t0);
      if (T > 0.0) out[i] = (r1 - r0) / T;
    }
  }
  return out;
}

OdometryModel with_cause(OdometryModel m, const Cause& c) {
  const diagnosis::CauseSpec& spec = diagnosis::cause_spec(c.id);
  for (const auto& p : spec.params) {
    if (p.field == nullptr) continue;
    for (const auto& e : c.parameters) {
      if (e.name == p.name && std::isfinite(e.value)) m.*(p.field) = e.value;
    }
  }
  return m;
}

std::vector<double> residual_component(const MotionData& d, const OdometryModel& m, int k) {
  std::vector<double> r(d.windows.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < d.windows.size(); ++i) {
    const diagnosis::WindowResidual w = diagnosis::window_residual(d, d.windows[i], m);
    if (w.valid && !(k == 0 && w.heading_only)) r[i] = w.r[k];
  }
  return r;
}

reports::Plot plot(std::string name, std::string kind, std::string title, std::string xl, std::string xu,
                   std::string yl, std::string yu, std::string note) {
  reports::Plot p;
  p.name = std::move(name);
  p.kind = std::move(kind);
  p.title = std::move(title);
  p.x_label = std::move(xl);
  p.x_unit = std::move(xu);
  p.y_label = std::move(yl);
  p.y_unit = std::move(yu);
  p.note = std::move(note);
  return p;
}

}  // namespace

reports::DiagnosedLog diagnosed_log(const std::string& log, const diagnosis::Diagnosis& d) {
  reports::DiagnosedLog out{log, d.reference, {}, d.verdict};
  for (const Cause& c : d.causes) {
    if (!c.detected) continue;
    reports::KeptCause k;
    k.id = c.id;
    k.identifiable = c.identifiable;
    for (const auto& p : c.parameters) k.parameters.push_back({p.name, p.value, p.lo, p.hi});
    if (!c.gains.empty())
      k.gain = reports::FindingGain{c.gains.front().metric, c.gains.front().before, c.gains.front().after};
    out.causes.push_back(std::move(k));
  }
  return out;
}

std::vector<reports::Plot> diagnosis_plots(const std::string& ds, const MotionData& data, const diagnosis::Diagnosis& d,
                                           const DiagnosisPlotOptions& options) {
  std::vector<reports::Plot> out;
  const OdometryModel nominal;
  OdometryModel all = nominal;
  all.sigma_x = d.noise_sigma_x > 0.0 ? d.noise_sigma_x : all.sigma_x;
  all.sigma_y = d.noise_sigma_y > 0.0 ? d.noise_sigma_y : all.sigma_y;
  all.sigma_theta = d.noise_sigma_theta > 0.0 ? d.noise_sigma_theta : all.sigma_theta;
  bool any_odometry = false;
  for (const Cause& c : d.causes) {
    if (!c.detected || c.channel != "odometry") continue;
    any_odometry = true;
    all = with_cause(all, c);
  }
  // Residual against the revealing covariate, before and after each kept mean cause.
  for (const Cause& c : d.causes) {
    if (!c.detected || c.channel != "odometry") continue;
    const Revealing rv = revealing(c.id);
    if (rv.component < 0) continue;
    const std::vector<double> x = covariate(data, rv.covariate);
    const bool heading = rv.component == 2;
    const double to_unit = heading ? to_deg(1.0) : to_mm(1.0);
    auto scaled = [&](std::vector<double> v) {
      for (double& e : v) e *= to_unit;
      return v;
    };
    const bool rate = rv.covariate == "turn_rate" || rv.covariate == "turn_rate_change";
    std::vector<double> xs = x;
    if (rate)
      for (double& e : xs) e = to_deg(e);
    reports::Plot p = plot(reports::key_part(ds + "_residual_" + c.id), "binned",
                           fmt::format("{}: {} residual against {}, before and after {}", ds,
                                       heading ? "heading" : "along-track", rv.covariate, c.id),
                           rv.covariate,
                           rv.covariate == "speed"              ? "m/s"
                           : rv.covariate == "turn_rate"        ? "deg/s"
                           : rv.covariate == "turn_rate_change" ? "deg/s²"
                                                                : "m",
                           heading ? "heading residual (reference − prediction), mean per bin"
                                   : "along-track residual (reference − prediction), mean per bin",
                           heading ? "deg" : "mm",
                           fmt::format("{} windows in {} equal-count bins; the nominal model vs the nominal model "
                                       "with {} alone at its fitted values",
                                       data.windows.size(), options.bins, c.id));
    p.series.push_back(
        binned_means("nominal model", xs, scaled(residual_component(data, nominal, rv.component)), options.bins));
    p.series.push_back(binned_means(
        "with " + c.id, xs, scaled(residual_component(data, with_cause(nominal, c), rv.component)), options.bins));
    out.push_back(std::move(p));
  }
  // The time-offset profile (timed references: relations carry no time to shift).
  if (data.reference != diagnosis::ReferenceKind::kRelations && options.offset_points >= 3) {
    reports::PlotSeries dev{"deviance 2·(NLL − min)", {}, {}};
    std::vector<double> nll;
    for (std::size_t i = 0; i < options.offset_points; ++i) {
      const double o = -options.offset_range + 2.0 * options.offset_range * static_cast<double>(i) /
                                                   static_cast<double>(options.offset_points - 1);
      OdometryModel m = all;
      m.time_offset = o;
      dev.x.push_back(to_mm(o));  // s → ms, the same factor
      nll.push_back(diagnosis::negative_log_likelihood(data, m, {}));
    }
    const double lo = *std::min_element(nll.begin(), nll.end());
    for (double v : nll) dev.y.push_back(2.0 * (v - lo));
    reports::Plot p = plot(reports::key_part(ds + "_offset_profile"), "profile", ds + ": time-offset profile",
                           "odometry time − reference time", "ms", "deviance 2·(NLL − min)", "",
                           fmt::format("{} offsets over ±{:.0f} ms, the other parameters held at the kept causes' "
                                       "values{}; the diagnosis's 95% interval is where its re-fitted profile "
                                       "crosses 3.84",
                                       options.offset_points, options.offset_range * 1e3,
                                       any_odometry ? "" : " (none kept: the nominal model)"));
    const std::vector<double> ends = {dev.x.front(), dev.x.back()};
    p.series.push_back(std::move(dev));
    p.series.push_back({"χ²₁(0.95) = 3.84", ends, {3.84, 3.84}});
    for (const Cause& c : d.causes) {
      if (c.detected && c.id == diagnosis::cause::kTimeOffset && !c.parameters.empty()) {
        const auto& e = c.parameters.front();
        p.series.push_back({"kept offset, 95% interval", {to_mm(e.lo), to_mm(e.value), to_mm(e.hi)}, {0.0, 0.0, 0.0}});
      }
    }
    out.push_back(std::move(p));
  }
  // Error distributions: per-window translation and heading error, nominal vs all kept causes.
  std::vector<double> tn, tk, hn, hk;
  for (const auto& w : data.windows) {
    const auto a = diagnosis::window_residual(data, w, nominal);
    const auto b = diagnosis::window_residual(data, w, all);
    if (!a.valid || !b.valid) continue;
    if (!a.heading_only && !b.heading_only) {
      tn.push_back(to_mm(std::hypot(a.r[0], a.r[1])));
      tk.push_back(to_mm(std::hypot(b.r[0], b.r[1])));
    }
    hn.push_back(std::abs(to_deg(a.r[2])));
    hk.push_back(std::abs(to_deg(b.r[2])));
  }
  const std::string after = any_odometry ? "with the kept causes" : "with the kept causes (none)";
  if (!tn.empty()) {
    reports::Plot p = plot(reports::key_part(ds + "_translation_error_cdf"), "cdf",
                           ds + ": per-window translation error", "translation error", "mm", "fraction of windows", "",
                           fmt::format("{} windows of {:.3g} s", tn.size(), d.noise_window_s));
    p.series.push_back(cdf_samples("nominal model", tn, options.cdf_points));
    p.series.push_back(cdf_samples(after, tk, options.cdf_points));
    out.push_back(std::move(p));
  }
  if (!hn.empty()) {
    reports::Plot p =
        plot(reports::key_part(ds + "_heading_error_cdf"), "cdf", ds + ": per-window heading error", "|heading error|",
             "deg", "fraction of windows", "", fmt::format("{} windows of {:.3g} s", hn.size(), d.noise_window_s));
    p.series.push_back(cdf_samples("nominal model", hn, options.cdf_points));
    p.series.push_back(cdf_samples(after, hk, options.cdf_points));
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace locbench::experiments
