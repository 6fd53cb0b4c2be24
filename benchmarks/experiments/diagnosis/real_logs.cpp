// Experiment diagnosis/real_logs: `diagnose` on every real log of ../shared/datasets that has a
// reference — the Freiburg logs (ODOM against their .relations) and the MRCLAM robots (velocity
// odometry against Vicon ground truth) — and on the thesis's Table 3.1 histogram. For each: the
// causes found with their parameters and 95% intervals, the held-out gain, what is left
// unexplained, and the verdict. Logs that are absent are recorded as skipped. Any user's log
// (`--log L [--relations R] [--ground-truth G]`, or objects in "datasets") goes through the same
// real-log harness as the other real-data experiments.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "algorithms/diagnosis/diagnosis.h"
#include "algorithms/diagnosis/scale_checks.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/registry.h"
#include "pipelines/diagnosis_plots.h"
#include "pipelines/real_log_harness.h"

namespace locbench::experiments::diagnosis_real_logs {

const ExperimentInfo kInfo{
    .name = "diagnosis/real_logs",
    .description =
        "What the nominal odometry model gets wrong on real logs (Freiburg relations, MRCLAM Vicon) and "
        "on the thesis's Table 3.1 histogram: named causes, fitted parameters, held-out gain"};

struct Options {
  nlohmann::json datasets = freiburg_and_mrclam_logs();
  double false_alarm = 0.01;
  double window_s = 1.0;
  // The thesis's histogram, as diagnosis::read_histogram reads it.
  nlohmann::json table_3_1 = {{"residual", "encoder_minus_compass_heading_increment"},
                              {"unit", "deg"},
                              {"edges", {-5, -4, -3, -2, -1, 0, 1, 2, 3, 4, 5}},
                              {"counts", {3, 15, 5, 177, 20, 419, 11, 139, 7, 13}}};
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("datasets", o.datasets, "", Range{}, "catalog names or user files (real_log_harness.h)");
  v.field("false_alarm", o.false_alarm, "", open(0.0, 1.0), "false-alarm rate of each test");
  v.field("window_s", o.window_s, "s", positive(), "residual window");
  v.field("table_3_1", o.table_3_1, "", Range{}, "histogram diagnosed beside the logs");
}

// A diagnosis in the report: the diagnosed log, counts, each detected cause's parameters and
// gain, and a note naming the causes and what stays unexplained.
void record_diagnosis(const diagnosis::Diagnosis& d, const std::string& ds, std::size_t n,
                      reports::ExperimentResults& out) {
  out.diagnoses.push_back(diagnosed_log(ds, d));
  out.results.push_back(
      reports::make_estimate("diagnose", ds, "causes_detected", "", static_cast<double>(d.detected.size()), 0.0, n));
  out.results.push_back(reports::make_estimate("diagnose", ds, "unexplained_structures", "",
                                               static_cast<double>(d.unexplained.size()), 0.0, n));
  std::string found;
  for (const auto& c : d.causes) {
    if (!c.detected) continue;
    std::string params;
    for (const auto& p : c.parameters) {
      const double se = (p.hi - p.lo) / (2.0 * 1.959963984540054);
      out.results.push_back(
          reports::make_estimate("diagnose", ds, c.id + "." + p.name, "", p.value, std::isfinite(se) ? se : 0.0, n));
      params += fmt::format("{}{} = {:.5g} [{:.5g}, {:.5g}]", params.empty() ? "" : ", ", p.name, p.value, p.lo, p.hi);
    }
    std::string gain;
    if (!c.gains.empty()) {
      const auto& g = c.gains.front();
      gain = fmt::format("; held-out {} {:.4g} → {:.4g} ({:+.1f}%)", g.metric, g.before, g.after, 100.0 * g.relative());
      out.results.push_back(reports::make_estimate("diagnose", ds, c.id + ".gain_relative", "", g.relative(), 0.0, n));
    }
    found += fmt::format("\n  - {} ({}{}){}", c.id, params, c.identifiable ? "" : ", confounded", gain);
  }
  std::string unexplained;
  for (const auto& u : d.unexplained) {
    unexplained +=
        fmt::format("{}{} of {} against {} (p = {:.2g}, strength {:.3g}: {})", unexplained.empty() ? "" : "; ", u.test,
                    u.residual, u.variable.empty() ? "-" : u.variable, u.p_value, u.strength, u.reason);
  }
  out.notes.push_back(fmt::format("{} — reference: {}. {}{}{}", ds, d.reference, d.verdict,
                                  found.empty() ? "" : "\n  Causes:" + found,
                                  unexplained.empty() ? "" : "\n  Unexplained: " + unexplained));
}

// One log's diagnosis, with the independent scale checks and the plots.
struct Outcome {
  std::optional<diagnosis::Diagnosis> diagnosis;
  std::optional<reports::DatasetRef> dataset;
  std::optional<reports::CaseNote> note;
  std::optional<diagnosis::ScaleChecks> checks;
  std::vector<reports::Plot> plots;  // residuals before/after each kept cause, offset profile, CDFs
  std::size_t samples = 0;
};

Outcome diagnose_real_log(const RealLogSpec& spec, const std::string& name, const diagnosis::DiagnosisOptions& opt,
                          const std::filesystem::path& data_root) {
  Outcome o;
  // A user's missing or malformed file is an InputError (exit 2) from here; catalog data
  // that is absent or unreadable becomes a skipped or failed case.
  LoadedRealLog loaded = load_real_log(spec, data_root);
  if (loaded.status != "ok") {
    o.note = reports::CaseNote{"diagnosis/" + name, loaded.status, loaded.reason};
    return o;
  }
  std::optional<diagnosis::MotionData> motion;
  try {
    motion = diagnosis::build_motion_data(loaded.log, opt.windows);
    o.diagnosis = diagnosis::diagnose_log(loaded.log, *motion, opt);
  } catch (const InputError& err) {
    if (!spec.from_catalog) throw;  // a user's log: exit 2
    o.note = reports::CaseNote{"diagnosis/" + name, "failed", err.what()};
    return o;
  }
  // The independent checks, at the time offset the diagnosis kept (0 when none).
  double offset = 0.0;
  for (const auto& c : o.diagnosis->causes) {
    if (c.id == "sensor_time_offset" && c.detected && !c.parameters.empty()) offset = c.parameters[0].value;
  }
  o.checks = diagnosis::scale_checks(*motion, offset);
  o.plots = diagnosis_plots(name, *motion, *o.diagnosis);
  o.dataset = loaded.dataset;
  o.samples = loaded.log.odometry.size() + loaded.log.encoders.size();
  return o;
}

// The independent checks in the report, and where a diagnosed distance scale disagrees with them.
void record_checks(const std::string& name, const Outcome& o, const diagnosis::ScaleChecks& c,
                   reports::ExperimentResults& out) {
  const std::size_t n = o.samples;
  out.results.push_back(reports::make_estimate("check", name, "path_length_ratio", "", c.path_length_ratio, 0.0, n));
  out.results.push_back(reports::make_estimate("check", name, "ls_velocity_scale", "", c.ls_velocity_scale, 0.0, n));
  out.results.push_back(reports::make_estimate("check", name, "ls_turn_rate_scale", "", c.ls_turn_scale, 0.0, n));
  out.results.push_back(
      reports::make_estimate("check", name, "median_window_ratio", "", c.median_window_ratio, 0.0, n));
  out.notes.push_back(
      fmt::format("{} — independent checks over the same {} windows (algorithms/diagnosis/scale_checks.h): "
                  "path-length ratio {:.3f}, least-squares velocity scale {:.3f}, least-squares "
                  "turn-rate scale {:.3f}, median window ratio {:.3f}",
                  name, c.windows, c.path_length_ratio, c.ls_velocity_scale, c.ls_turn_scale, c.median_window_ratio));
  // The distance scale the checks measure: velocity_scale's, or with drive stalls kept the
  // mean distance scale they imply (the speed when moving is not what a path length sees).
  const auto& kept = o.diagnosis->detected;
  const bool stalls = std::find(kept.begin(), kept.end(), "drive_stall") != kept.end();
  for (const auto& cause : o.diagnosis->causes) {
    if (!cause.detected || cause.parameters.empty()) continue;
    if (cause.id == "drive_stall" && cause.extra.contains("mean_distance_scale")) {
      const double m = cause.extra["mean_distance_scale"].get<double>();
      out.results.push_back(reports::make_estimate("diagnose", name, "drive_stall.mean_distance_scale", "", m, 0.0, n));
      if (auto why = diagnosis::scale_disagreement(name, m, m, m, c, 0.02, "mean distance scale of drive_stall");
          !why.empty())
        out.notes.push_back(why);
    } else if (cause.id == "velocity_scale" && !stalls) {
      const auto& p = cause.parameters.front();
      if (auto why = diagnosis::scale_disagreement(name, p.value, p.lo, p.hi, c); !why.empty()) {
        out.notes.push_back(why);
      }
    }
  }
}

class DiagnosisRealLogs final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& cfg, const RunOptions& options) const override {
    reports::ExperimentResults out = start_results(options_json(cfg));
    diagnosis::DiagnosisOptions opt;
    opt.false_alarm = cfg.false_alarm;
    opt.windows.duration = cfg.window_s;
    const auto specs = real_log_specs(cfg.datasets, name());
    const auto names = real_log_names(specs);
    // Every log on its own thread (results are recorded in the configured order afterwards).
    std::vector<Outcome> outcomes(names.size());
    parallel_tasks(options.threads, specs.size(),
                   [&](std::size_t i) { outcomes[i] = diagnose_real_log(specs[i], names[i], opt, options.data_root); });
    for (std::size_t i = 0; i < names.size(); ++i) {
      Outcome& o = outcomes[i];
      if (o.note) out.cases.push_back(*o.note);
      if (!o.diagnosis) continue;
      out.datasets.push_back(*o.dataset);
      record_diagnosis(*o.diagnosis, names[i], o.samples, out);
      for (auto& p : o.plots) out.plots.push_back(std::move(p));
      if (o.checks && o.diagnosis->reference.find("compass heading") == std::string::npos) {
        record_checks(names[i], o, *o.checks, out);
      }
    }
    options.report_progress(0.9);
    const auto h = diagnosis::read_histogram(cfg.table_3_1, "table_3_1");
    const auto d = diagnosis::diagnose_histogram(h, "thesis Table 3.1", opt);
    out.datasets.push_back({"thesis_table_3_1", "thesis Table 3.1 (transcribed)", text_checksum(cfg.table_3_1.dump()),
                            h.counts.size(), 0.0});
    double n = 0.0;
    for (double c : h.counts) n += c;
    record_diagnosis(d, "thesis_table_3_1", static_cast<std::size_t>(n), out);
    options.report_progress(1.0);
    return out;
  }
};

const Registration<DiagnosisRealLogs> diagnosis_real_logs_registration(kInfo);

}  // namespace locbench::experiments::diagnosis_real_logs
