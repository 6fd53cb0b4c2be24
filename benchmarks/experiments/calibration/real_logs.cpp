// Experiment calibration/real_logs: the ML calibration on real data.
// - censi_khepera (lstraight, l90 and their subsets): odometry and laser pose jointly, beside the
//   published solutions of Censi et al. (IEEE T-RO 2013) with their uncertainty.
// - Freiburg logs (odometry against the local .relations) and MRCLAM 6 (velocities against
//   Vicon; the parameters are velocity scales): calibrate on the first half of each log, and
//   measure the relative-motion error of calibrated vs uncalibrated odometry on the second.
#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <iterator>
#include <mutex>
#include <optional>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/held_out_evaluation.h"
#include "algorithms/calibration/ml_calibration.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "datasets/catalog/calibration_catalog.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/censi_results_reader.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/registry.h"
#include "pipelines/real_log_harness.h"

namespace locbench::experiments::calibration_real_logs {
using io::CensiPublishedResult, io::read_censi_results;
using locbench::calibration::calibrate_ml, locbench::calibration::CalibratedParameter,
    locbench::calibration::calibration_data_from_relations, locbench::calibration::calibration_data_from_velocities,
    locbench::calibration::CalibrationData, locbench::calibration::evaluate_held_out,
    locbench::calibration::HeldOutEvaluation, locbench::calibration::MlCalibrationOptions,
    locbench::calibration::MlCalibrationResult, locbench::calibration::NoiseModelKind,
    locbench::calibration::RelationSampleOptions, locbench::calibration::SampleIntervalOptions;
using locbench::catalog::DatasetEntry, locbench::catalog::find_dataset,
    locbench::catalog::load_catalog_calibration_records;

const ExperimentInfo kInfo{.name = "calibration/real_logs",
                           .description =
                               "ML odometry calibration on real data: Censi's Khepera sets beside the published "
                               "solutions; Freiburg and MRCLAM calibrated on one half, evaluated on the other"};

reports::MetricResult one_value(const std::string& method, const std::string& dataset, const std::string& variant,
                                const std::string& unit, double value) {
  return reports::make_metric(method, dataset, variant, unit, "held_out_rmse", std::vector<double>{value});
}

struct Options {
  std::vector<std::string> censi_parts = {"lstraight", "lstraight_0", "lstraight_1", "lstraight_2",
                                          "l90",       "l90_0",       "l90_1",       "l90_2"};
  nlohmann::json relations_logs = freiburg_logs();
  double relation_max_duration_s = 10.0;
  nlohmann::json velocity_logs = {"mrclam6_robot1", "mrclam6_robot2", "mrclam6_robot3", "mrclam6_robot4",
                                  "mrclam6_robot5"};
  double velocity_time_offset_s = 0.25;
  double training_fraction = 0.5;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("censi_parts", o.censi_parts, "", Range{}, "Censi's Khepera sets");
  v.field("relations_logs", o.relations_logs, "", Range{}, "logs calibrated on their relations");
  v.field("relation_max_duration_s", o.relation_max_duration_s, "s", positive(), "longest relation used as a sample");
  v.field("velocity_logs", o.velocity_logs, "", Range{}, "logs calibrated on velocities and truth");
  v.field("velocity_time_offset_s", o.velocity_time_offset_s, "s", any_finite(),
          "odometry time offset of the velocity logs");
  v.field("training_fraction", o.training_fraction, "", open(0.0, 1.0),
          "share of each log calibrated on (the rest evaluates)");
}

// Parameter estimates that agree with Censi et al.'s published ones, of those compared.
struct Agreement {
  int agree = 0, compared = 0;
};

// One of Censi et al.'s Khepera sets, calibrated with their noise model (per-component) and
// outlier rejection (4 × 1%) and compared with their published solution.
void compare_with_censi(const std::string& part, const DatasetEntry& censi, const std::filesystem::path& data_root,
                        reports::ExperimentResults& out, Agreement& agreement) {
  const std::filesystem::path results = data_root / censi.path / (part + "_results.json");
  if (!std::filesystem::exists(results)) {
    // The case name ends in the results' dataset key, so gates know these were skipped.
    out.cases.push_back({"calibration/censi_" + reports::key_part(part), "skipped",
                         "dataset not found at " + results.string() + " (set LOCBENCH_DATA)"});
    return;
  }
  const CalibrationData data =
      calibration::calibration_data_from_records(load_catalog_calibration_records(censi, data_root, part));
  const CensiPublishedResult pub = read_censi_results(results);
  MlCalibrationOptions o;
  o.noise.kind = NoiseModelKind::kPerComponent;
  o.outliers = {4, 0.01};
  const MlCalibrationResult r = calibrate_ml(data, o);
  const std::string ds = "censi_" + reports::key_part(part);
  out.datasets.push_back({ds, (data_root / censi.path / (part + ".tuple.gz")).string(),
                          file_checksum(data_root / censi.path / (part + ".tuple.gz")), data.samples.size(), 0.0});
  const double published[6] = {pub.left_radius(), pub.right_radius(), pub.axle,
                               pub.sensor_x,      pub.sensor_y,       pub.sensor_theta};
  const char* names[6] = {"r_L", "r_R", "b", "sensor_x", "sensor_y", "sensor_theta"};
  const char* units[6] = {"m", "m", "m", "m", "m", "rad"};
  reports::PublishedComparison t{
      "Censi et al. 2013, " + part + "_results.json", "calibrated parameters", "m, rad", {}, ""};
  std::string worst;
  double worst_ratio = 0.0;
  for (int i = 0; i < 6; ++i) {
    const CalibratedParameter& p = r.parameter(names[i]);
    reports::MetricResult m =
        reports::make_estimate("ml", ds, names[i], units[i], p.value, p.standard_error, r.samples_used);
    m.identifiable = p.identifiable;
    if (!p.identifiable) m.note = p.reason;
    out.results.push_back(std::move(m));
    const double bound = 2.0 * std::hypot(pub.standard_error(i), p.standard_error);
    t.rows.push_back({names[i], published[i], p.value});
    if (std::isfinite(bound)) t.rows.back().tolerance = bound;
    const double ratio = std::abs(p.value - published[i]) / bound;
    ++agreement.compared;
    if (ratio <= 1.0) ++agreement.agree;
    if (ratio > worst_ratio) {
      worst_ratio = ratio;
      worst = names[i];
    }
  }
  t.note = fmt::format(
      "Agreement criterion per parameter: |ours − published| ≤ 2·√(σ_pub² + σ_ours²). "
      "Largest ratio to that bound: {:.2f} ({}); {} of {} samples used after 4 × 1% outlier "
      "rejection.",
      worst_ratio, worst, r.samples_used, r.samples_used + r.samples_rejected);
  t.claim = "Censi et al.'s ML calibration of the Khepera (wheel radii, axle, laser pose) on " + part;
  t.tolerance_basis = "per parameter 2·√(σ_pub² + σ_ours²), both estimates' standard errors";
  out.published.push_back(std::move(t));
}

// A log calibrated on its first `fraction` and evaluated on the rest.
void record_held_out(const std::string& name, const CalibrationData& d, const MlCalibrationOptions& o,
                     const std::string& path, double fraction, reports::ExperimentResults& out) {
  const HeldOutEvaluation h = evaluate_held_out(d, o, fraction);
  const std::string ds = reports::key_part(name);
  out.datasets.push_back({ds, path, file_checksum(path.substr(0, path.find('#'))), d.samples.size(), 0.0});
  for (const CalibratedParameter& p : h.calibration.parameters) {
    reports::MetricResult m =
        reports::make_estimate("ml_first_half", ds, p.name, "", p.value, p.standard_error, h.calibration.samples_used);
    m.identifiable = p.identifiable;
    if (!p.identifiable) m.note = p.reason;
    out.results.push_back(std::move(m));
  }
  out.results.push_back(
      one_value("odometry_nominal", ds, "held_out_rpe_translation_rmse", "m", h.nominal_translation.rmse));
  out.results.push_back(
      one_value("odometry_calibrated", ds, "held_out_rpe_translation_rmse", "m", h.calibrated_translation.rmse));
  out.results.push_back(
      one_value("odometry_nominal", ds, "held_out_rpe_rotation_rmse", "rad", h.nominal_rotation.rmse));
  out.results.push_back(
      one_value("odometry_calibrated", ds, "held_out_rpe_rotation_rmse", "rad", h.calibrated_rotation.rmse));
  out.notes.push_back(
      fmt::format("{}: calibrated on {} samples, evaluated on {}: translation RMSE {:.4g} → {:.4g} m "
                  "({:+.1f}%), rotation RMSE {:.4g} → {:.4g} rad ({:+.1f}%).",
                  name, h.training_samples, h.evaluation_samples, h.nominal_translation.rmse,
                  h.calibrated_translation.rmse, -100 * h.translation_rmse_reduction, h.nominal_rotation.rmse,
                  h.calibrated_rotation.rmse, -100 * h.rotation_rmse_reduction));
}

// `part`'s datasets, results, published comparisons, cases, notes and plots after `out`'s.
void append_results(reports::ExperimentResults& out, reports::ExperimentResults part) {
  const auto move_all = [](auto& to, auto& from) { std::move(from.begin(), from.end(), std::back_inserter(to)); };
  move_all(out.datasets, part.datasets);
  move_all(out.results, part.results);
  move_all(out.published, part.published);
  move_all(out.cases, part.cases);
  move_all(out.notes, part.notes);
  move_all(out.plots, part.plots);
  move_all(out.diagnoses, part.diagnoses);
}

class CalibrationRealLogs final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& c, const RunOptions& options) const override {
    reports::ExperimentResults out = start_results(options_json(c));
    const std::vector<std::string>& parts = c.censi_parts;
    const auto rel_logs = real_log_specs(c.relations_logs, name() + ": relations_logs");
    const auto vel_logs = real_log_specs(c.velocity_logs, name() + ": velocity_logs");
    // Each Censi set and each log is calibrated on its own, side by side on the run's threads, and
    // appended to the report in this order (the same report for any number of threads).
    std::vector<std::function<void(reports::ExperimentResults&, Agreement&)>> jobs;
    const DatasetEntry* censi = find_dataset("censi_khepera");
    for (const std::string& part : parts) {
      jobs.push_back([&, part](reports::ExperimentResults& r, Agreement& a) {
        compare_with_censi(part, *censi, options.data_root, r, a);
      });
    }
    // Calibrates on each log of `specs` that loads; a missing catalog log is a skipped case.
    auto each_loaded = [&](const std::vector<RealLogSpec>& specs, const MlCalibrationOptions& o, auto samples_of) {
      for (const RealLogSpec& spec : specs) {
        jobs.push_back([&, spec, o, samples_of](reports::ExperimentResults& r, Agreement&) {
          LoadedRealLog loaded = load_real_log(spec, options.data_root);
          if (loaded.status == "failed") throw InputError(loaded.dataset.path, 0, loaded.reason);
          if (loaded.status != "ok") {
            r.cases.push_back(
                {"calibration/" + spec.name, loaded.status, "dataset not found at " + loaded.dataset.path});
            return;
          }
          record_held_out(spec.name, samples_of(loaded.log), o, loaded.dataset.path, c.training_fraction, r);
        });
      }
    };
    RelationSampleOptions local;
    local.max_duration = c.relation_max_duration_s;
    MlCalibrationOptions with_rotation_per_distance;
    with_rotation_per_distance.estimate_rotation_per_distance = true;
    each_loaded(rel_logs, with_rotation_per_distance,
                [local](const Log& log) { return calibration_data_from_relations(log, local); });
    SampleIntervalOptions intervals;
    intervals.odometry_time_offset = c.velocity_time_offset_s;
    MlCalibrationOptions per_component;
    per_component.noise.kind = NoiseModelKind::kPerComponent;
    each_loaded(vel_logs, per_component,
                [intervals](const Log& log) { return calibration_data_from_velocities(log, intervals); });

    std::vector<reports::ExperimentResults> results(jobs.size());
    std::vector<Agreement> agreements(jobs.size());
    std::atomic<std::size_t> done{0};
    std::mutex progress_mutex;
    parallel_tasks(options.threads, jobs.size(), [&](std::size_t i) {
      jobs[i](results[i], agreements[i]);
      const std::size_t d = ++done;
      const std::lock_guard<std::mutex> lock(progress_mutex);
      options.report_progress(static_cast<double>(d) / static_cast<double>(jobs.size()));
    });
    Agreement agreement;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      append_results(out, std::move(results[i]));
      agreement.agree += agreements[i].agree;
      agreement.compared += agreements[i].compared;
    }
    if (agreement.compared > 0) {
      out.notes.push_back(
          fmt::format("Censi's Khepera data: {} of {} parameter estimates agree with the published solutions "
                      "within 2·√(σ_pub² + σ_ours²).",
                      agreement.agree, agreement.compared));
    }
    for (std::size_t i = parts.size(); i < jobs.size(); ++i) append_results(out, std::move(results[i]));
    options.report_progress(1.0);
    return out;
  }
};

const Registration<CalibrationRealLogs> calibration_real_logs_registration(kInfo);

}  // namespace locbench::experiments::calibration_real_logs
