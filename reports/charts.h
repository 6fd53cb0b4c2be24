#pragma once
// Charts of a report as gnuplot scripts (pure functions; `locbench report` runs gnuplot on them):
// trajectories, error against distance travelled, histograms of per-run metric values, empirical
// CDFs of error samples, binned residual means and likelihood profiles.
#include <string>
#include <utility>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

// Equal-width bins over the pooled range of every sample set; counts[s][b] of set s in bin b.
struct Histogram {
  double low = 0.0;
  double width = 1.0;
  std::vector<std::vector<int>> counts;
};
// `bins` bins (≥ 1); non-finite samples are left out; a degenerate range gets width 1e-9·scale.
Histogram histogram(const std::vector<std::vector<double>>& samples, int bins);

// A plot of named sample sets whose y axis the chart derives from the samples — a histogram's
// counts, an empirical CDF's fractions: the one builder of every such kind.
Plot sample_plot(std::string kind, std::string y_label, std::string name, std::string title, std::string x_label,
                 std::string x_unit, std::vector<PlotSeries> samples, std::string note);

// A histogram plot (kind "histogram", y "runs") of named sample sets, e.g. one metric's values
// per method.
Plot histogram_plot(std::string name, std::string title, std::string x_label, std::string x_unit,
                    std::vector<PlotSeries> samples, std::string note);

// The histograms a reader wants from a report's metrics: for every (dataset, variant) that is an
// error over Monte-Carlo runs with at least `min_values` values, one plot with each method's
// values; at most `max_plots`.
std::vector<Plot> metric_histograms(const ExperimentResults& results, std::size_t min_values = 5,
                                    std::size_t max_plots = 6);

// The empirical CDF of a sample as step corners: x sorted, y = i/n after the i-th value (finite
// values only; at most `max_points` corners, evenly thinned, the last one always kept).
struct CdfSteps {
  std::vector<double> x, y;
};
CdfSteps empirical_cdf(std::vector<double> samples, std::size_t max_points = 400);

// In a "scan_pair" plot: whether the series holds segments (name ends in "lines" or "matches").
bool is_segment_series(const std::string& name);

// The gnuplot script drawing `plot` as SVG on stdout (terminal svg, no JavaScript).
std::string plot_script(const Plot& plot);

}  // namespace locbench::reports
