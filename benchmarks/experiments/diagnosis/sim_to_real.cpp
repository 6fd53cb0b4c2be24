// Experiment diagnosis/sim_to_real: does the model the diagnosis extends make the simulation
// behave like the measured robot? For every real log with a reference (Freiburg ODOM against
// .relations, MRCLAM Dataset 6 velocities against Vicon), over a bounded stretch of the log
// (`span_s`, 0 = whole log): diagnose it, build its synthetic twins (datasets/diagnosis/
// twin_scenario.h: the log's odometry replayed, truth simulated under the nominal model and under
// the nominal model plus every kept cause, noise floors moment-matched) and compare the
// nominal-model window residuals of the log with those of each twin, per window length and
// component, by the two-sample Kolmogorov–Smirnov distance D and its p-value. The gain of the
// extension is the reduction of D (ratio D_extended / D_nominal; the goal is ≤ 0.5 on MRCLAM).
//
// Why Kolmogorov–Smirnov rather than the energy distance: D is distribution-free, needs no
// permutations (a permutation p-value for the energy distance costs ~1000 × n² here, beyond the
// default suite's time budget), and it is exactly the largest vertical gap between the CDFs the
// report draws. Its p-value assumes independent windows; neighbouring windows of a log are
// correlated, so the p-values are optimistic and serve as a scale, not a test decision.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "datasets/io/odometry_interpolation.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/registry.h"
#include "pipelines/real_log_harness.h"
#include "pipelines/twin/twin_comparison.h"

namespace locbench::experiments::diagnosis_sim_to_real {
using io::odometry_trajectory;

const ExperimentInfo kInfo{
    .name = "diagnosis/sim_to_real",
    .description =
        "The diagnosis run back through the simulator: each real log's synthetic twin (its odometry replayed, truth "
        "simulated) under the nominal and under the extended model, compared with the log by the Kolmogorov–Smirnov "
        "distance of the window residuals (1 s and 10 s windows; relations on Freiburg), per component"};

struct Outcome {
  std::optional<reports::CaseNote> note;
  std::optional<reports::DatasetRef> dataset;
  std::vector<sim::ComponentComparison> cells;
  sim::Twin twin;
  std::string reference;
  std::size_t windows = 0;
};

struct Options {
  nlohmann::json datasets = freiburg_and_mrclam_logs();
  double false_alarm = 0.01;
  double window_s = 1.0;
  double long_window_s = 10.0;
  double start_s = 0.0;
  double span_s = 300.0;
  int twin_runs = 2;
  double goal_ratio = 0.5;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("datasets", o.datasets, "", Range{}, "catalog names or user files (real_log_harness.h)");
  v.field("false_alarm", o.false_alarm, "", open(0.0, 1.0), "false-alarm rate of each test");
  v.field("window_s", o.window_s, "s", positive(), "short residual window");
  v.field("long_window_s", o.long_window_s, "s", positive(), "long residual window");
  v.field("start_s", o.start_s, "s", non_negative(), "start of the span after the log's first record");
  v.field("span_s", o.span_s, "s", non_negative(), "span of each log (0 = whole log)");
  v.field("twin_runs", o.twin_runs, "", at_least(1), "simulated twins per model");
  v.field("goal_ratio", o.goal_ratio, "", positive(), "D_extended / D_nominal counted as halved");
}

// One log: diagnosed over the configured stretch, its twins built and compared with it.
Outcome compare_with_twins(const RealLogSpec& spec, const std::string& name, const Options& cfg,
                           const RunOptions& options) {
  diagnosis::DiagnosisOptions opt;
  opt.false_alarm = cfg.false_alarm;
  opt.windows.duration = cfg.window_s;
  Outcome o;
  // A user's missing or malformed file is an InputError (exit 2) from here; catalog data
  // that is absent or unreadable becomes a skipped or failed case.
  const LoadedRealLog loaded = load_real_log(spec, options.data_root);
  if (loaded.status != "ok") {
    o.note = reports::CaseNote{"sim_to_real/" + name, loaded.status, loaded.reason};
    return o;
  }
  try {
    const Log& full = loaded.log;
    const Trajectory odo = odometry_trajectory(full);
    double t0 = !full.encoders.empty() ? full.encoders.front().t : odo.empty() ? 0.0 : odo.start_time();
    if (!full.truth.empty()) t0 = std::max(t0, full.truth.front().t);
    const double from = t0 + cfg.start_s;
    const double to = cfg.span_s > 0.0 ? from + cfg.span_s : std::numeric_limits<double>::infinity();
    const Log log = restrict_log(full, from, to);
    const diagnosis::Diagnosis d = diagnosis::diagnose_log(log, opt);
    sim::TwinOptions twin_options;
    twin_options.calibration_seed = options.seed;
    o.twin = sim::build_twin(log, d, twin_options);
    o.reference = d.reference;
    o.cells = sim::compare_twins(log, o.twin, {opt.windows.duration, cfg.long_window_s}, cfg.twin_runs, options.seed);
    o.windows = o.cells.empty() ? 0 : o.cells.front().real.size();
    const auto span = log.time_span();
    o.dataset = loaded.dataset;  // the restricted stretch's records and duration
    o.dataset->records = log.record_count();
    o.dataset->duration_s = span.second - span.first;
  } catch (const InputError& err) {
    if (!spec.from_catalog) throw;  // a user's log: exit 2
    o.note = reports::CaseNote{"sim_to_real/" + name, "failed", err.what()};
  }
  return o;
}

// A log's KS distances: results per window and component, the table's lines, how many halved.
struct KsSummary {
  std::vector<reports::MetricResult> results;
  std::string table;
  std::size_t halved = 0;
  double overall = 1.0;  // mean ratio D_extended / D_nominal
};

KsSummary ks_summary(const std::string& ds, const Outcome& o, double goal) {
  KsSummary s;
  double sum_nom = 0.0, sum_ext = 0.0;
  for (const auto& c : o.cells) {
    const std::string v = c.window + "_" + c.component;
    const std::size_t n = c.real.size();
    s.results.push_back(reports::make_estimate("nominal_twin", ds, "ks_distance_" + v, "", c.nominal.d, 0.0, n));
    s.results.push_back(reports::make_estimate("extended_twin", ds, "ks_distance_" + v, "", c.extended.d, 0.0, n));
    s.results.push_back(reports::make_estimate("nominal_twin", ds, "ks_p_value_" + v, "", c.nominal.p_value, 0.0, n));
    s.results.push_back(reports::make_estimate("extended_twin", ds, "ks_p_value_" + v, "", c.extended.p_value, 0.0, n));
    s.results.push_back(
        reports::make_estimate("extended_vs_nominal", ds, "ks_distance_ratio_" + v, "", c.ratio(), 0.0, n));
    s.halved += c.ratio() <= goal ? 1 : 0;
    sum_nom += c.nominal.d;
    sum_ext += c.extended.d;
    s.table += fmt::format("\n  {:<9} {:<5} D nominal {:.3f} (p {:.2g}), extended {:.3f} (p {:.2g}), ratio {:.2f}{}",
                           c.window, c.component, c.nominal.d, c.nominal.p_value, c.extended.d, c.extended.p_value,
                           c.ratio(), c.ratio() <= goal ? "" : "  ← not halved");
  }
  s.overall = sum_nom > 0.0 ? sum_ext / sum_nom : 1.0;
  return s;
}

// The noise floors: moment-matched per twin, and the diagnosis's own ML fit of the nominal one
// (an independent estimate of the same quantity as the nominal twin's).
std::vector<reports::MetricResult> noise_floor_results(const std::string& ds, const Outcome& o) {
  std::vector<reports::MetricResult> out;
  const auto& nfl = o.twin.nominal.motion_noise;
  const auto& efl = o.twin.extended.motion_noise;
  const std::array<std::pair<const char*, const char*>, 3> comps{{{"x", "m"}, {"y", "m"}, {"theta", "rad"}}};
  const std::array<double, 3> nominal_floor{nfl.sigma_along, nfl.sigma_left, nfl.sigma_heading};
  const std::array<double, 3> extended_floor{efl.sigma_along, efl.sigma_left, efl.sigma_heading};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string v = std::string("noise_floor_sigma_") + comps[k].first;
    out.push_back(reports::make_estimate("nominal_twin", ds, v, comps[k].second, nominal_floor[k], 0.0, o.windows));
    out.push_back(reports::make_estimate("extended_twin", ds, v, comps[k].second, extended_floor[k], 0.0, o.windows));
    out.push_back(
        reports::make_estimate("diagnosis_ml", ds, v, comps[k].second, o.twin.diagnosis_floor[k], 0.0, o.windows));
  }
  return out;
}

std::string log_note(const std::string& ds, const Outcome& o, const KsSummary& ks) {
  std::string causes;
  for (const auto& m : o.twin.causes) causes += fmt::format("\n  - {}: {}", m.id, m.how);
  if (causes.empty()) causes = "\n  - none kept: the extended twin equals the nominal one";
  const auto& nf = o.twin.nominal.motion_noise;
  const auto& ef = o.twin.extended.motion_noise;
  return fmt::format(
      "{} — reference: {}; {} paired {} windows. Extended twin's causes:{}{}\n  Noise floor per {:g} s window "
      "(moment-matched): nominal σ = ({:.3g} m, {:.3g} m, {:.3g} rad), extended σ = ({:.3g} m, {:.3g} m, {:.3g} "
      "rad); "
      "the diagnosis's own nominal floor ({:.3g} m, {:.3g} m, {:.3g} rad).\n  KS distance of the residual "
      "distributions, real vs twin:{}\n  Mean ratio {:.2f}: {} ({} of {} distances halved).",
      ds, o.reference, o.windows, o.cells.empty() ? "" : o.cells.front().window, causes,
      o.twin.not_simulated.empty() ? ""
                                   : "\n  NOT simulated: " + fmt::format("{}", fmt::join(o.twin.not_simulated, ", ")),
      nf.window, nf.sigma_along, nf.sigma_left, nf.sigma_heading, ef.sigma_along, ef.sigma_left, ef.sigma_heading,
      o.twin.diagnosis_floor[0], o.twin.diagnosis_floor[1], o.twin.diagnosis_floor[2], ks.table, ks.overall,
      o.twin.causes.empty()         ? "no cause kept, so nothing to gain: both twins are the same"
      : ks.halved == o.cells.size() ? "the extended model halves every distance of the nominal one"
                                    : "the extended model does NOT halve every distance of the nominal one",
      ks.halved, o.cells.size());
}

// One chart per component at the short windows (relations on Freiburg): the residuals' CDFs.
std::vector<reports::Plot> cdf_plots(const std::string& ds, const Outcome& o) {
  std::vector<reports::Plot> out;
  for (const auto& c : o.cells) {
    if (c.window == "10s") continue;
    reports::Plot p;
    p.name = reports::key_part("cdf_" + ds + "_" + c.window + "_" + c.component);
    p.kind = "cdf";
    p.title = fmt::format("{}: {} residual over {} windows, real vs twins", ds, c.component, c.window);
    p.x_label = c.component + " residual (reference − nominal odometry)";
    p.x_unit = c.component == "theta" ? "rad" : "m";
    p.y_label = "cumulative fraction";
    p.series = {{"real log", {}, c.real}, {"nominal twin", {}, c.nominal_twin}, {"extended twin", {}, c.extended_twin}};
    p.note = fmt::format("KS D nominal {:.3f}, extended {:.3f} (ratio {:.2f})", c.nominal.d, c.extended.d, c.ratio());
    out.push_back(std::move(p));
  }
  return out;
}

class DiagnosisSimToReal final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& cfg, const RunOptions& options) const override {
    reports::ExperimentResults out = start_results(options_json(cfg));
    out.seeds = {options.seed};
    const auto specs = real_log_specs(cfg.datasets, name());
    const auto names = real_log_names(specs);
    std::vector<Outcome> outcomes(names.size());
    parallel_tasks(options.threads, names.size(),
                   [&](std::size_t i) { outcomes[i] = compare_with_twins(specs[i], names[i], cfg, options); });
    options.report_progress(0.95);

    std::vector<std::string> missed;
    std::size_t mrclam = 0, mrclam_halved = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const Outcome& o = outcomes[i];
      if (o.note) out.cases.push_back(*o.note);
      if (!o.dataset) continue;
      out.datasets.push_back(*o.dataset);
      const std::string& ds = names[i];
      KsSummary ks = ks_summary(ds, o, cfg.goal_ratio);
      for (auto& r : ks.results) out.results.push_back(std::move(r));
      for (auto& r : noise_floor_results(ds, o)) out.results.push_back(std::move(r));
      out.results.push_back(
          reports::make_estimate("extended_vs_nominal", ds, "ks_distance_ratio_mean", "", ks.overall, 0.0, o.windows));
      if (ds.rfind("mrclam", 0) == 0) {
        ++mrclam;
        if (ks.halved == o.cells.size())
          ++mrclam_halved;
        else
          missed.push_back(fmt::format("{} ({} of {} distances halved, mean ratio {:.2f})", ds, ks.halved,
                                       o.cells.size(), ks.overall));
      }
      out.notes.push_back(log_note(ds, o, ks));
      for (auto& p : cdf_plots(ds, o)) out.plots.push_back(std::move(p));
    }
    if (mrclam > 0) {
      out.notes.push_back(
          mrclam_halved == mrclam
              ? fmt::format("Goal met: on all {} MRCLAM robots the extended model at least halves every "
                            "KS distance of the nominal one.",
                            mrclam)
              : fmt::format("Goal NOT met on {} of {} MRCLAM robots (the extended model should halve every "
                            "KS distance of the nominal one): {}.",
                            mrclam - mrclam_halved, mrclam, fmt::format("{}", fmt::join(missed, "; "))));
    }
    if (out.datasets.empty()) {
      out.notes.push_back("No real log was found (set LOCBENCH_DATA to the datasets folder): nothing was compared.");
    }
    options.report_progress(1.0);
    return out;
  }
};

const Registration<DiagnosisSimToReal> diagnosis_sim_to_real_registration(kInfo);

}  // namespace locbench::experiments::diagnosis_sim_to_real
