#pragma once
// What the simulation gets wrong: `diagnose_log` takes a log, the nominal model it declares
// (PARAM records) and the reference it carries (TRUEPOS, .relations or a compass), and
//  1. computes residuals of the nominal model against the reference (motion_windows.h,
//     odometry_model.h; compass readings against ground truth: compass_channel.h; landmark
//     range-bearing observations against ground truth and a map: landmark_channel.h);
//  2. runs the residual battery (residual_tests.h) at a Bonferroni-divided level;
//  3. fits every applicable catalog cause (cause_catalog.h) by maximum likelihood with a 95%
//     interval on every parameter, and keeps causes by forward selection: the cause with the
//     largest likelihood-ratio statistic enters while LR ≥ χ²_k(1 − α/m), α the false-alarm
//     level per log and m the number of causes tried on the channel;
//  4. measures each kept cause's gain on held-out windows (every third block of 10 windows is
//     held out; the fits use the rest): the nominal model extended by the cause alone against
//     the nominal model, in predictive log-likelihood and relative-pose error;
//  5. reports residual structure no kept cause explains, confounded causes with the
//     combination the data determine, and a one-sentence verdict.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "core/log.h"

namespace locbench::diagnosis {

// Throws InputError for logs without odometry or reference, too short, or with implausible units.
Diagnosis diagnose_log(const Log& log, const DiagnosisOptions& options = {});
// The same on the log's motion data, built by the caller with build_motion_data(log,
// options.windows), so that a caller using the data afterwards builds them once.
Diagnosis diagnose_log(const Log& log, const MotionData& data, const DiagnosisOptions& options);

// A histogram of residuals (e.g. thesis Table 3.1):
// {"residual": "...", "unit": "deg"|"rad"|"mm"|"m", "edges": [...], "counts": [...]}.
struct ResidualHistogram {
  std::string residual;
  std::string unit;
  std::vector<double> edges;  // SI after reading (rad or m)
  std::vector<double> counts;
};
// Throws InputError (file, what was expected) for malformed histograms.
ResidualHistogram read_histogram(const nlohmann::json& j, const std::string& file);
Diagnosis diagnose_histogram(const ResidualHistogram& h, const std::string& name, const DiagnosisOptions& options = {});

// The report, "schema": "locbench.diagnosis/1".
nlohmann::json to_json(const Diagnosis& d);

// The fitted models of a report (`diagnose --report` output, or its "models" object), for a
// filter: {"odometry_kind": "encoder"|"velocity", "odometry_window_s": s, "odometry": {…},
// "landmark": {…}} (each part optional). Strict: an unknown key, a wrong type or a value out of
// range → UsageError naming the key.
struct FittedModels {
  std::optional<OdometryModel> odometry;
  std::string odometry_kind;
  double odometry_window_s = 1.0;  // the odometry σ are per window of this length [s]
  std::optional<LandmarkModel> landmark;
};
FittedModels read_fitted_models(const nlohmann::json& report_or_models);

}  // namespace locbench::diagnosis
