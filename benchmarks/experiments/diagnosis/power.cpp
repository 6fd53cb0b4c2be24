// Experiment diagnosis/power: how well `diagnose` finds what is hidden. For every catalog effect
// the generator can hide (datasets/diagnosis/hidden_effects.h) and every magnitude of a grid from
// barely detectable to large, `runs` logs on random paths; per magnitude the detection rate
// (power), the rate at which the effect is named first, the 95%-interval coverage of the true
// parameter and the rate of a positive held-out gain; and on `null_runs` logs with nothing
// hidden, the false-alarm rate (anything detected or left unexplained). The detection limit of a
// cause is the smallest magnitude from which the power stays ≥ 0.9.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/units.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"

namespace locbench::experiments::diagnosis_power {

const ExperimentInfo kInfo{
    .name = "diagnosis/power",
    .description =
        "Hidden effects in simulated logs: detection power against effect size, interval coverage, "
        "held-out gain, and the false-alarm rate on logs with nothing hidden",
    .in_default_suite = false};  // ~1 min on 2 cores; `locbench run diagnosis`

struct PowerCase {
  std::string id;  // "" for the null case
  double magnitude = 0.0;
};

struct PowerSetup {
  std::vector<PowerCase> cases;  // null first
  int null_runs = 20;
  int waypoints = 16;
  diagnosis::DiagnosisOptions options;
  nlohmann::json config;
};

// The magnitude grids (units: sim::hidden_effect_ids()).
nlohmann::json default_grids() {
  return {{"wheel_diameter_ratio", {2.5e-4, 5e-4, 1e-3, 2e-3, 4e-3}},
          {"wheelbase_scale", {5e-4, 1e-3, 2e-3, 4e-3, 1e-2}},
          {"mean_diameter_scale", {5e-4, 1e-3, 2e-3, 4e-3, 1e-2}},
          {"encoder_quantization", {2, 4, 8, 16}},
          {"compass_quantization", {deg(0.25), deg(0.5), deg(1.0), deg(2.0)}},
          {"compass_bias", {deg(0.05), deg(0.1), deg(0.2), deg(0.5), deg(1.0)}},
          {"compass_disturbance", {deg(0.5), deg(1.0), deg(2.0), deg(5.0), deg(10.0)}},
          {"wheel_slip", {0.01, 0.03, 0.1, 0.3}},
          {"odometry_noise_growth", {1e-7, 1e-6, 1e-5, 1e-4}},
          {"velocity_scale", {5e-4, 1e-3, 2e-3, 5e-3, 2e-2}},
          {"turn_rate_scale", {5e-4, 1e-3, 2e-3, 5e-3, 2e-2}},
          {"turn_rate_bias", {1e-4, 3e-4, 1e-3, 3e-3, 1e-2}},
          {"sensor_time_offset", {0.002, 0.005, 0.01, 0.02, 0.05}}};
}

struct Options {
  int runs = 5;
  int null_runs = 40;
  double false_alarm = 0.01;
  int waypoints = 16;
  nlohmann::json grids = default_grids();
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "logs per effect and magnitude");
  v.field("null_runs", o.null_runs, "", non_negative(), "logs with nothing hidden");
  v.field("false_alarm", o.false_alarm, "", open(0.0, 1.0), "false-alarm rate of each test");
  v.field("waypoints", o.waypoints, "", at_least(2), "waypoints of each generated path");
  v.field("grids", o.grids, "", Range{}, "effect id → magnitudes (sim::hidden_effect_ids())");
}

bool velocity_effect(const std::string& id) {
  return id == "velocity_scale" || id == "turn_rate_scale" || id == "turn_rate_bias";
}

const diagnosis::Cause* find(const diagnosis::Diagnosis& d, const std::string& id) {
  for (const auto& c : d.causes) {
    if (c.id == id && (c.detected || c.channel != "compass" || id != "sensor_time_offset")) return &c;
  }
  return nullptr;
}

class DiagnosisPower final : public MonteCarloExperiment<Options, PowerSetup> {
 public:
  PowerSetup setup(const Options& cfg, const McPlan&) const override {
    PowerSetup s;
    s.config = options_json(cfg);
    s.null_runs = cfg.null_runs;
    s.waypoints = cfg.waypoints;
    s.options.false_alarm = cfg.false_alarm;
    for (const auto& [id, grid] : cfg.grids.items()) {
      for (const auto& m : grid) s.cases.push_back({id, m.get<double>()});
    }
    return s;
  }
  int tasks(const PowerSetup& s, const McPlan& plan) const override {
    return s.null_runs + static_cast<int>(s.cases.size()) * plan.runs;
  }

  nlohmann::json run_task(const PowerSetup& s, const McPlan& plan, int task) const override {
    const bool null = task < s.null_runs;
    const PowerCase c = null ? PowerCase{} : s.cases[static_cast<std::size_t>((task - s.null_runs) / plan.runs)];
    sim::GeneratorOptions o;
    o.waypoints = s.waypoints;
    o.velocity_odometry = velocity_effect(c.id);
    if (c.id == "compass_quantization") o.waypoints = std::max(o.waypoints, 60);  // many headings
    std::vector<sim::HiddenEffect> effects;
    if (!null) effects.push_back({c.id, c.magnitude});
    const auto g = sim::generate_log(effects, plan.run_seed(task), o);
    const auto d = diagnosis::diagnose_log(g.log, s.options);
    nlohmann::json r{{"null", null}, {"id", c.id}, {"magnitude", c.magnitude}};
    r["detected_any"] = !d.detected.empty();
    r["unexplained"] = d.unexplained.size();
    if (null) return r;
    r["detected"] = std::find(d.detected.begin(), d.detected.end(), c.id) != d.detected.end();
    r["first"] = !d.detected.empty() && d.detected.front() == c.id;
    const diagnosis::Cause* cause = find(d, c.id);
    bool covered = false;
    double gain = std::nan("");
    if (cause && cause->detected) {
      for (const auto& [key, truth] : g.truth) {
        if (key.rfind(c.id + ".", 0) != 0) continue;
        const std::string pname = key.substr(c.id.size() + 1);
        for (const auto& p : cause->parameters) {
          // Tolerance for the approximate models: slip (one loss per window, fixed fraction)
          // 30%, the disturbance disc 25%.
          const double tol = c.id == "wheel_slip" ? 0.3 : c.id == "compass_disturbance" ? 0.25 : 0.0;
          if (p.name == pname) covered = truth >= p.lo - tol * std::abs(truth) && truth <= p.hi + tol * std::abs(truth);
        }
      }
      if (!cause->gains.empty()) gain = cause->gains.front().relative();
    }
    r["covered"] = covered;
    r["gain_relative"] = std::isfinite(gain) ? nlohmann::json(gain) : nlohmann::json(nullptr);
    return r;
  }

  reports::ExperimentResults summarise(const PowerSetup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.config);
    for (int k = 0; k < static_cast<int>(records.size()); ++k) out.seeds.push_back(plan.run_seed(k));
    std::vector<double> fa, fa_detect;
    for (int k = 0; k < s.null_runs; ++k) {
      const auto& r = records[static_cast<std::size_t>(k)];
      fa_detect.push_back(r.at("detected_any").get<bool>() ? 1.0 : 0.0);
      fa.push_back(r.at("detected_any").get<bool>() || r.at("unexplained").get<std::size_t>() > 0 ? 1.0 : 0.0);
    }
    if (!fa.empty()) {
      auto m = reports::make_metric("diagnose", "null_logs", "false_alarm_rate", "", "logs", fa);
      out.results.push_back(m);
      out.results.push_back(
          reports::make_metric("diagnose", "null_logs", "false_detection_rate", "", "logs", fa_detect));
    }
    std::map<std::string, reports::Plot> plots;
    std::vector<std::string> limits;
    std::map<std::string, std::vector<std::pair<double, double>>> power_of;
    for (std::size_t c = 0; c < s.cases.size(); ++c) {
      std::vector<double> det, first, cov, gain;
      for (int k = 0; k < plan.runs; ++k) {
        const auto& r = records[static_cast<std::size_t>(s.null_runs) + c * static_cast<std::size_t>(plan.runs) +
                                static_cast<std::size_t>(k)];
        det.push_back(r.at("detected").get<bool>() ? 1.0 : 0.0);
        first.push_back(r.at("first").get<bool>() ? 1.0 : 0.0);
        if (r.at("detected").get<bool>()) {
          cov.push_back(r.at("covered").get<bool>() ? 1.0 : 0.0);
          gain.push_back(!r.at("gain_relative").is_null() && r.at("gain_relative").get<double>() > 0.0 ? 1.0 : 0.0);
        }
      }
      const auto& pc = s.cases[c];
      const std::string ds = fmt::format("{}_{:.3g}", pc.id, pc.magnitude);
      auto add = [&](const char* variant, const std::vector<double>& v) {
        if (v.empty()) return;
        auto m = reports::make_metric("diagnose", ds, variant, "", "logs", v);
        m.better = "higher";
        out.results.push_back(m);
      };
      add("power", det);
      add("named_first", first);
      add("ci95_covers_truth", cov);
      add("positive_heldout_gain", gain);
      double p = 0.0;
      for (double v : det) p += v;
      p /= static_cast<double>(det.size());
      power_of[pc.id].push_back({pc.magnitude, p});
    }
    reports::Plot plot{"power_curves",
                       "error_vs_distance",
                       "Detection power against effect size",
                       "effect size (log10 of the magnitude)",
                       "",
                       "power",
                       "",
                       {},
                       ""};
    for (const auto& [id, pts] : power_of) {
      reports::PlotSeries series{id, {}, {}};
      std::optional<double> limit;
      for (std::size_t i = pts.size(); i-- > 0;) {
        if (pts[i].second >= 0.9)
          limit = pts[i].first;
        else
          break;
      }
      for (const auto& [m, p] : pts) {
        series.x.push_back(std::log10(std::abs(m)));
        series.y.push_back(p);
      }
      plot.series.push_back(series);
      limits.push_back(limit ? fmt::format("{} ≥ {:.3g}", id, *limit)
                             : fmt::format("{}: power < 0.9 on the whole grid", id));
    }
    plot.note = fmt::format("{} logs per magnitude; magnitude units per cause in datasets/diagnosis/hidden_effects.cpp",
                            plan.runs);
    out.plots.push_back(plot);
    double far = 0.0;
    for (double v : fa) far += v;
    out.notes.push_back(
        fmt::format("False alarms on {} logs with nothing hidden: {} (rate {:.3f}); the stated level is {} per channel "
                    "(odometry, compass) for causes, and the same level spread over the residual battery for "
                    "unexplained structure.",
                    fa.size(), far, fa.empty() ? 0.0 : far / static_cast<double>(fa.size()), s.options.false_alarm));
    std::string lim = "Measured detection limits (power ≥ 0.9 from this magnitude up): ";
    for (std::size_t i = 0; i < limits.size(); ++i) lim += (i ? "; " : "") + limits[i];
    out.notes.push_back(lim + ".");
    return out;
  }
};

const Registration<DiagnosisPower> diagnosis_power_registration(kInfo);

}  // namespace locbench::experiments::diagnosis_power
