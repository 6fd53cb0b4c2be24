#pragma once
// How predictivity cells (predictivity.h) appear in a report: per log and metric a table row per
// method (real value, each twin's interval, covered or not), the across-log summary per metric as
// results, and two pictures — per log the real value of each method beside the
// twins' predictive intervals, and per metric the predictions against the real values with the
// identity line.
#include <map>
#include <string>
#include <vector>

#include "pipelines/predictivity.h"
#include "reports/report.h"

namespace locbench::experiments {

// Lines of a note: one per cell, "method: real 0.187 | nominal [a, b] covered | extended …".
std::string cell_lines(const std::vector<PredictivityCell>& cells, const std::string& unit);

// Fewer compared cells than this say little about a correlation or a ranking: no such results.
inline constexpr std::size_t kMinCorrelatedCells = 8;

// Results of one metric's summary, under method "nominal_twin" / "extended_twin" and dataset
// "all_logs": the fraction of cells covered, and with ≥ kMinCorrelatedCells compared cells
// Pearson r, Spearman ρ and MMRV.
std::vector<reports::MetricResult> predictivity_results(const std::string& metric, const MetricPredictivity& m);

// The share of `cells` residual comparisons (log × component) whose twin residuals the KS block
// bootstrap cannot tell from the log's (p > 0.05), for each twin: "residual_ks_indistinguishable_fraction".
std::vector<reports::MetricResult> residual_ks_results(std::size_t cells, std::size_t nominal, std::size_t extended);

// The per-log picture: methods along x (in the order of `cells`), the real value as a point and
// the nominal and extended twins' 95% predictive intervals as bars beside it.
reports::Plot interval_plot(const std::string& name, const std::string& title, const std::string& unit,
                            const std::vector<PredictivityCell>& cells);
// The per-metric scatter: each twin's prediction (median) against the real value, with y = x.
reports::Plot scatter_plot(const std::string& name, const std::string& title, const std::string& unit,
                           const std::vector<PredictivityCell>& cells);

}  // namespace locbench::experiments
