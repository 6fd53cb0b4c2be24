// `locbench calibrate METHOD INPUT [--report out.json]`: calibrate odometry from measured data.
//   umbmark-classic, umbmark-improved: INPUT is the UMBmark JSON a person fills in (README);
//   ml: INPUT is a log (CARMEN with ENCODER + TRUEPOS, or ODOM + --relations), a Censi tuple
//       file, or a catalog dataset name (`locbench list`), e.g. censi_khepera:l90, aces.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <iostream>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/ml_calibration.h"
#include "algorithms/calibration/umbmark_design_model.h"
#include "algorithms/calibration/umbmark_improved.h"
#include "baselines/calibration/umbmark_classic.h"
#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "cli/estimate_judgement.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/output_file.h"
#include "datasets/catalog/calibration_catalog.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/catalog/log_spec.h"
#include "datasets/io/censi_tuple_reader.h"
#include "datasets/io/umbmark_input_reader.h"
#include "reports/finish_report.h"

namespace locbench::cli {
using io::read_censi_tuples, io::read_umbmark_input;
using locbench::baselines::calibration::classic_umbmark, locbench::baselines::calibration::ClassicUmbmarkResult;
using locbench::calibration::analyze_umbmark_design, locbench::calibration::calibrate_ml,
    locbench::calibration::CalibratedParameter, locbench::calibration::calibration_data_from_encoders,
    locbench::calibration::calibration_data_from_relations, locbench::calibration::calibration_data_from_velocities,
    locbench::calibration::calibration_data_from_wheel_speed_tuples, locbench::calibration::CalibrationData,
    locbench::calibration::improved_umbmark, locbench::calibration::ImprovedUmbmarkResult,
    locbench::calibration::MlCalibrationOptions, locbench::calibration::MlCalibrationResult,
    locbench::calibration::NoiseModelKind, locbench::calibration::ParameterFinding,
    locbench::calibration::RelationSampleOptions, locbench::calibration::SampleIntervalOptions,
    locbench::calibration::UmbmarkDesign, locbench::calibration::UmbmarkDesignFinding,
    locbench::calibration::UmbmarkIdentifiabilityOptions, locbench::calibration::UmbmarkParameterSet;
using locbench::catalog::DatasetEntry, locbench::catalog::find_dataset, locbench::catalog::is_calibration_dataset,
    locbench::catalog::load_catalog_calibration_records, locbench::catalog::load_log_spec, locbench::catalog::LoadedLog,
    locbench::catalog::LogSpec;
namespace {

struct CalibrateArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::string method;
  std::string input;
  std::string report;
  std::string relations;
  std::string data;
};

using reports::make_estimate;

// UMBmark: every output parameter; E_d and E_b carry the Fisher standard error of the square
// (at the nominal robot, with the runs' own scatter), the rest follow by linearisation.
reports::ExperimentResults calibrate_umbmark(const CalibrateArgs& a, bool improved) {
  const UmbmarkInput in = read_umbmark_input(a.input);
  reports::ExperimentResults out;
  const std::string method = improved ? "umbmark_improved" : "umbmark_classic";
  out.experiment = "calibrate/" + method;
  out.description = improved ? "Improved UMBmark (thesis eq. 2.16–2.27) on a measured square"
                             : "Classic UMBmark (Borenstein & Feng, eq. 2.3–2.13) on a measured square";
  out.datasets.push_back({"umbmark_input", a.input, file_checksum(a.input), in.runs.size(), 0.0});
  out.configuration = {{"method", method}, {"input", a.input}};
  const UmbmarkCentroids c = umbmark_centroids(in.runs);
  UmbmarkIdentifiabilityOptions idopt;
  idopt.run_sigma = c.run_sigma > 0.0 ? c.run_sigma : 0.02;
  idopt.runs_per_direction = std::max(1, std::min(c.runs_cw, c.runs_ccw));
  const UmbmarkDesignFinding f =
      analyze_umbmark_design(improved ? UmbmarkDesign::kSquareWithLegTicks : UmbmarkDesign::kSquare,
                             improved ? UmbmarkParameterSet::kImproved : UmbmarkParameterSet::kClassic, in.nominal,
                             in.encoder, in.side_length, {}, idopt);
  auto finding = [&f](const std::string& name) -> const ParameterFinding* {
    for (const auto& p : f.report.parameters) {
      if (p.name == name) return &p;
    }
    return nullptr;
  };
  auto remedy = [&f](const std::string& name) {
    for (const auto& [p, r] : f.remedies) {
      if (p == name) return "; to determine it: " + r;
    }
    return std::string();
  };
  const std::size_t n = in.runs.size();
  const std::string ds = "input";
  auto add = [&](const std::string& name, const std::string& unit, double value, double se,
                 const std::string& depends_on) {
    reports::MetricResult m = make_estimate(method, ds, name, unit, value, se, n);
    const ParameterFinding* pf = finding(depends_on);
    if (pf && !pf->identifiable) {
      m = make_estimate(method, ds, name, unit, value, std::numeric_limits<double>::infinity(), n);
      m.note = (name == depends_on ? "" : "follows from " + depends_on + ", which is not determined: ") + pf->reason +
               remedy(depends_on);
    }
    out.results.push_back(std::move(m));
  };
  const double se_d = finding("E_d") ? finding("E_d")->standard_error : 0.0;
  const double se_b = finding("E_b") ? finding("E_b")->standard_error : 0.0;
  const double Bn = in.nominal.wheelbase;
  if (!improved) {
    const ClassicUmbmarkResult r = classic_umbmark(in);
    const double Ed = r.E_d;
    add("E_d", "", Ed, se_d, "E_d");
    add("E_b", "", r.E_b, se_b, "E_b");
    reports::MetricResult es = reports::make_metric(method, ds, "E_s", "", "input", std::vector<double>{r.E_s});
    es.note = "tape-measured input (eq. 2.15), not estimated from the runs";
    out.results.push_back(std::move(es));
    add("D_L", "m", r.D_L, 2.0 * r.D_a / ((Ed + 1) * (Ed + 1)) * se_d, "E_d");
    add("D_R", "m", r.D_R, 2.0 * r.D_a / ((1 / Ed + 1) * (1 / Ed + 1) * Ed * Ed) * se_d, "E_d");
    add("B", "m", r.B_actual, Bn * se_b, "E_b");
    add("c_L", "", r.c_L, 2.0 / ((Ed + 1) * (Ed + 1)) * se_d, "E_d");
    add("c_R", "", r.c_R, 2.0 / ((1 / Ed + 1) * (1 / Ed + 1) * Ed * Ed) * se_d, "E_d");
  } else {
    const ImprovedUmbmarkResult r = improved_umbmark(in);
    add("E_d", "", r.E_d, se_d, "E_d");
    add("E_b", "", r.E_b, se_b, "E_b");
    add("E_o", "", r.E_o, finding("E_o") ? finding("E_o")->standard_error : 0.0, "E_o");
    // D_L, D_R, c_L, c_R carry the absolute scale E_o; B carries E_b.
    add("D_L", "m", r.D_L, 0.0, "E_o");
    add("D_R", "m", r.D_R, 0.0, "E_o");
    add("B", "m", r.B_actual, Bn * se_b, "E_b");
    add("c_L", "m/tick", r.c_L, 0.0, "E_o");
    add("c_R", "m/tick", r.c_R, 0.0, "E_o");
  }
  out.results.push_back(
      reports::make_metric(method, ds, "e_max_syst_of_input", "m", "input", std::vector<double>{c.e_max_syst}));
  out.notes.push_back(
      fmt::format("Identifiability ({}; {}): Fisher rank {} of {}, condition number {:.3g}, per-run σ {:.3f} m "
                  "from the runs' scatter. Standard errors of E_d and E_b are Fisher's; derived quantities "
                  "are linearised from them.",
                  to_string(f.design), to_string(f.parameter_set), f.report.rank, f.report.parameter_count,
                  f.report.condition_number, idopt.run_sigma));
  return out;
}

// The ML calibration's input: a catalog dataset name (optionally name:part), a Censi tuple
// file, or a log file.
// Options per input kind, as in calibration/real_logs: scan-matched or Vicon references get the
// per-component noise model (Censi's data also his 4 × 1% outlier rejection); Freiburg
// relations the odometry-propagated one with a rotation-per-distance term.
CalibrationData ml_input(const CalibrateArgs& a, reports::DatasetRef& ref, MlCalibrationOptions& o) {
  const std::filesystem::path root = a.data.empty() ? catalog::data_root() : std::filesystem::path(a.data);
  const std::string name = a.input.substr(0, a.input.find(':'));
  const std::string part = a.input.find(':') == std::string::npos ? "" : a.input.substr(a.input.find(':') + 1);
  const DatasetEntry* entry = find_dataset(name);
  if (entry != nullptr && !a.relations.empty()) {
    throw UsageError("--relations " + a.relations + ": " + a.input +
                     " is a catalog dataset, calibrated against its own reference; --relations applies to a "
                     "log file");
  }
  if (entry == nullptr && !a.data.empty()) {
    throw UsageError("--data " + a.data + ": applies to a catalog dataset name (`locbench list`), and " + a.input +
                     " is not one");
  }
  if (entry != nullptr && is_calibration_dataset(*entry)) {
    ref = {a.input, (root / entry->path).string(), file_checksum(root / entry->path), 0, 0.0};
    o.noise.kind = NoiseModelKind::kPerComponent;
    if (entry->name == "censi_khepera") o.outliers = {4, 0.01};
    return calibration::calibration_data_from_records(load_catalog_calibration_records(*entry, root, part));
  }
  if (entry == nullptr && a.input.find(".tuple") != std::string::npos) {
    if (!a.relations.empty()) {
      throw UsageError("--relations " + a.relations + ": a Censi tuple file brings its own reference");
    }
    o.noise.kind = NoiseModelKind::kPerComponent;
    o.outliers = {4, 0.01};
    const auto tuples = read_censi_tuples(a.input);
    ref = {a.input, a.input, file_checksum(a.input), tuples.size(), 0.0};
    CalibrationData data = calibration_data_from_wheel_speed_tuples(tuples);
    data.source = a.input;  // errors about the samples name the file
    return data;
  }
  LogSpec spec;
  spec.name = a.input;
  spec.log = entry != nullptr ? entry->name : a.input;
  spec.relations = a.relations;
  const LoadedLog loaded = load_log_spec(spec, root);
  const Log& log = loaded.log;
  ref = loaded.dataset;
  if (entry != nullptr) {
    if (!log.relations.empty()) {
      RelationSampleOptions local;
      local.max_duration = 10.0;  // local relations only; loop closures span minutes
      o.estimate_rotation_per_distance = true;
      return calibration_data_from_relations(log, local);
    }
    if (!log.encoders.empty()) return calibration_data_from_encoders(log);
    SampleIntervalOptions intervals;
    intervals.odometry_time_offset = 0.25;  // MRCLAM's velocities lead the Vicon motion
    o.noise.kind = NoiseModelKind::kPerComponent;
    return calibration_data_from_velocities(log, intervals);
  }
  // Relations given are used (before a log's own TRUEPOS), never silently ignored.
  if (!a.relations.empty()) return calibration_data_from_relations(log);
  if (!log.encoders.empty() && !log.truth.empty()) return calibration_data_from_encoders(log);
  if (!log.relations.empty()) return calibration_data_from_relations(log);
  if (!log.odometry.empty() && !log.truth.empty()) return calibration_data_from_velocities(log);
  throw InputError(a.input, 0,
                   "nothing to calibrate against: expected ENCODER with TRUEPOS records, ODOM with "
                   "--relations, or ODOM velocities with ground truth");
}

reports::ExperimentResults calibrate_ml_cmd(const CalibrateArgs& a, std::vector<std::string>& failures) {
  reports::ExperimentResults out;
  out.experiment = "calibrate/ml";
  out.description = "Maximum-likelihood odometry (and sensor-pose) calibration";
  reports::DatasetRef ref;
  MlCalibrationOptions opt;
  const CalibrationData data = ml_input(a, ref, opt);
  out.datasets.push_back(ref);
  const MlCalibrationResult r = calibrate_ml(data, opt);
  out.configuration = {
      {"method", "ml"}, {"input", a.input}, {"samples", r.samples_used}, {"rejected", r.samples_rejected}};
  const std::string ds = reports::key_part(std::filesystem::path(ref.name).filename().string());
  for (const CalibratedParameter& p : r.parameters) {
    reports::MetricResult m = make_estimate("ml", ds, p.name, "", p.value, p.standard_error, r.samples_used);
    m.identifiable = p.identifiable;
    if (!p.identifiable) m.note = p.reason;
    out.results.push_back(std::move(m));
  }
  // Judged before printed: nonsense is "not identifiable" or a failure, never "converged: yes".
  const EstimateJudgement judged = judge_estimates(out, true);
  failures = judged.impossible;
  const bool finite_fit = std::isfinite(r.residual_rms_translation) && std::isfinite(r.residual_rms_rotation) &&
                          std::isfinite(r.chi2_per_dof);
  if (!finite_fit) failures.push_back("the residual RMS or χ²/dof is not a finite number");
  if (!r.converged) failures.push_back("the solver did not converge");
  std::vector<std::string> undetermined;
  for (const reports::MetricResult& m : out.results) {
    if (!m.identifiable.value_or(true)) undetermined.push_back(m.variant);
  }
  std::string verdict = "converged: yes";
  if (!failures.empty()) {
    verdict = "failed: " + fmt::format("{}", fmt::join(failures, "; "));
  } else if (!undetermined.empty()) {
    verdict = "solver converged, but the data do not determine " + fmt::format("{}", fmt::join(undetermined, ", "));
  }
  out.notes.push_back(fmt::format(
      "{} samples used, {} rejected; residual RMS {:.4g} m / {:.4g} rad; χ²/dof {:.3g}; {}.", r.samples_used,
      r.samples_rejected, r.residual_rms_translation, r.residual_rms_rotation, r.chi2_per_dof, verdict));
  return out;
}

int calibrate(const CalibrateArgs& a, const std::string& command_line) {
  check_outputs({a.input, a.relations}, {{"--report", a.report}});
  // Every flag given is used or refused.
  if (a.method != "ml" && (!a.relations.empty() || !a.data.empty())) {
    throw UsageError(std::string(!a.relations.empty() ? "--relations" : "--data") + " applies to `calibrate ml`, not " +
                     a.method);
  }
  reports::Report report;
  std::vector<std::string> failures;
  if (a.method == "umbmark-classic" || a.method == "umbmark-improved") {
    report.body = calibrate_umbmark(a, a.method == "umbmark-improved");
    failures = judge_estimates(report.body, false).impossible;
  } else if (a.method == "ml") {
    report.body = calibrate_ml_cmd(a, failures);
  } else {
    throw UsageError("calibrate: METHOD must be umbmark-classic, umbmark-improved or ml, not \"" + a.method + "\"");
  }
  reports::ReportTail tail("calibrate", command_line, a.report);
  tail.print_summary = true;
  reports::finish_report(report, tail);
  if (!failures.empty()) {
    std::cerr << "locbench: calibrate: the estimate is not a result:\n";
    for (const std::string& f : failures) std::cerr << "  " << f << '\n';
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace

Action add_calibrate_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] = add_verb<CalibrateArgs>(app, "calibrate", "Calibrate odometry from measured data");
  cmd->add_option("method", args->method, "umbmark-classic, umbmark-improved or ml")->required();
  cmd->add_option("input", args->input,
                  "UMBmark JSON (umbmark-*), or for ml: a log, a .tuple file or a dataset name "
                  "(e.g. censi_khepera:l90, aces, mrclam6_robot1)")
      ->required();
  cmd->add_option("--report", args->report, "Write the report (JSON) here");
  cmd->add_option("--relations", args->relations, "ml: reference relations for a log's ODOM");
  add_data_option(cmd, args->data);
  return bag_topic_action(cmd, args, &CalibrateArgs::input,
                          [command_line](const CalibrateArgs& a) { return calibrate(a, command_line); });
}

}  // namespace locbench::cli
