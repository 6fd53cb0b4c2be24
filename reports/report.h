#pragma once
// The report model: what an experiment measured, with where and how it was measured.
// Written as JSON (reports/report_json.h) following reports/report.schema.json.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/dataset_ref.h"
#include "core/statistics.h"

namespace locbench::reports {

inline constexpr const char* kReportSchema = "locbench.report/1";

// Who produced the report: tool, build and machine.
struct Provenance {
  std::string tool_version;
  std::string git_revision;
  std::string compiler;
  std::string compiler_flags;
  std::string build_type;
  std::string host;
  std::string utc_time;  // ISO 8601, YYYY-MM-DDThh:mm:ssZ
  std::string command_line;
  std::optional<int> threads;  // worker threads of the Monte-Carlo runs (results never depend on it)
  std::optional<int> shards;   // set when the report was merged from this many shard reports
  // One id per locbench invocation, stamped into every report it writes (empty in reports made
  // before run ids existed): a folder whose reports carry different ids mixes runs.
  std::string run_id = {};
};

using locbench::DatasetRef;

// One metric of one method on one dataset, summarised over runs (or over samples of one run).
struct MetricResult {
  std::string method;   // e.g. "odometry_nominal"
  std::string dataset;  // e.g. "sim_corridor"
  std::string variant;  // the metric, e.g. "final_position_error"
  std::string unit;     // "m", "rad", "s", …
  // Which change is an improvement: "lower", "higher", "closer_to_zero" (signed errors) or
  // "stable" (estimates: any change beyond tolerance is a regression).
  std::string better = "lower";
  std::string over;  // what the statistics run over: "monte_carlo_runs", "relations", …
  Summary summary;
  std::vector<double> values;  // the samples summarised (may be empty for large series)
  // For estimated parameters: whether the data determine it, and in plain words why not and
  // what extra measurement would (empty when it is identifiable or the question does not apply).
  std::optional<bool> identifiable;
  std::string note;

  // Stable key `method/dataset/variant`, matched across runs by gates.
  std::string name() const { return method + "/" + dataset + "/" + variant; }
};

// A published table beside our numbers.
struct PublishedRow {
  std::string label;
  std::optional<double> published;
  std::optional<double> ours;
  // Optional: the same quantity computed another way (e.g. numerically where `ours` is closed
  // form). When ours and the check agree within the tolerance and the published figure does not,
  // the verdict is "the thesis is wrong" (reports/findings.h).
  std::optional<double> check = std::nullopt;
  // False for rows the verdict leaves out (e.g. per-run rows of runs not paired with the
  // thesis's, where only the mean row compares).
  bool compared = true;
  // Optional: this row's own tolerance (e.g. from both sides' standard errors), in place of the
  // table's.
  std::optional<double> tolerance = std::nullopt;
};
struct PublishedComparison {
  std::string source;  // e.g. "thesis Table 3.2"
  std::string quantity;
  std::string unit;
  std::vector<PublishedRow> rows;
  std::string note;  // where and why the figures differ
  // Optional, for the findings (reports/findings.h): the thesis's claim in one line, and the
  // tolerance within which a row counts as reproduced, |ours − published| ≤ max(tolerance,
  // relative_tolerance·|published|), with why that tolerance. Without a tolerance the table gets
  // no verdict.
  std::string claim = {};
  std::optional<double> tolerance = std::nullopt;           // in `unit`
  std::optional<double> relative_tolerance = std::nullopt;  // fraction of |published|
  std::string tolerance_basis = {};
};

// What a diagnosis kept on one log (diagnosis/real_logs): each cause with its fitted parameters'
// 95% intervals and its held-out gain, and the diagnosis's verdict.
struct FindingEstimate {
  std::string name;
  double value = 0.0, lo = 0.0, hi = 0.0;  // 95% interval [lo, hi]
};
struct FindingGain {
  std::string metric;
  double before = 0.0, after = 0.0;  // held-out, in the metric's units
};
struct KeptCause {
  std::string id;
  std::vector<FindingEstimate> parameters;
  std::optional<FindingGain> gain;  // the cause's primary held-out metric
  bool identifiable = true;         // false: confounded with another cause
};
struct DiagnosedLog {
  std::string log;
  std::string reference;
  std::vector<KeptCause> causes;
  std::string verdict;
};

// A series to plot: named (x, y) points, e.g. the truth's trajectory or a filter's error.
struct PlotSeries {
  std::string name;  // legend, e.g. "truth", "fixed_q_ekf"
  std::vector<double> x;
  std::vector<double> y;  // same length as x
};
// A chart a reader wants beside the numbers (drawn by `locbench report`). Kinds:
// "trajectory" (x, y in the plane, equal axes), "error_vs_distance" (error against distance
// travelled), "binned" (binned means of a residual against a covariate, lines with points),
// "profile" (a curve, e.g. the deviance against a time offset, lines), "histogram" (series y values are samples; x is
// unused and empty), "cdf" (series y values are samples drawn as overlaid empirical CDFs; x is unused and empty),
// "scan_pair" (laser scans in one robot frame, equal axes: a series whose name ends in "lines" or "matches" holds
// segments as consecutive point pairs, drawn as lines; any other series is points), "scatter" (points; a series
// named "identity" is drawn as a dashed line, one whose name ends in "intervals" holds vertical bars as point pairs).
struct Plot {
  std::string name;  // stable id within the experiment, e.g. "trajectories_run_0"
  std::string kind;
  std::string title;
  std::string x_label;
  std::string x_unit;
  std::string y_label;
  std::string y_unit;
  std::vector<PlotSeries> series;
  std::string note;  // what the chart shows, e.g. "run 0 of 20"
};

// A case that could not be run (missing dataset, bad input…), recorded instead of aborting.
struct CaseNote {
  std::string name;
  std::string status;  // "skipped" or "failed"
  std::string reason;
};

// What an experiment returns (no provenance: the CLI adds that).
struct ExperimentResults {
  std::string experiment;
  std::string description;
  std::vector<std::uint64_t> seeds;
  std::vector<DatasetRef> datasets;
  nlohmann::json configuration = nlohmann::json::object();
  std::vector<MetricResult> results;
  std::vector<PublishedComparison> published;
  std::vector<CaseNote> cases;
  std::vector<std::string> notes;       // findings in plain words (what agrees, what does not, why)
  std::vector<Plot> plots;              // optional series for charts (trajectories, error vs distance)
  std::vector<DiagnosedLog> diagnoses;  // optional: per log, what a diagnosis kept (findings)
};

struct Report {
  Provenance provenance;
  ExperimentResults body;
};

// A name made safe as one part of a result key: '/', ':' and '.' become '_'
// ("censi_khepera:l90" → "censi_khepera_l90", "12.64mm" → "12_64mm").
std::string key_part(std::string name);

// Builds a MetricResult from samples (Student-t 95% interval of the mean).
MetricResult make_metric(std::string method, std::string dataset, std::string variant, std::string unit,
                         std::string over, std::span<const double> values, bool keep_values = true);
// One estimate with its standard error (n = the measurements it came from): mean = value,
// stddev = standard error, ci95 = value ± 1.96·SE (normal), over = "estimate". A non-finite
// standard error (not identifiable) is written as stddev 0 with an empty interval around the
// value and identifiable = false.
MetricResult make_estimate(std::string method, std::string dataset, std::string variant, std::string unit, double value,
                           double standard_error, std::size_t n);

}  // namespace locbench::reports
