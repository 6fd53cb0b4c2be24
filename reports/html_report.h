#pragma once
// The report a person reads: one self-contained HTML page (no script, no network) with, per
// experiment, a summary table (mean ± 95% interval), estimates with intervals and
// identifiability, published-versus-ours tables, charts (trajectories, error against distance,
// histograms of per-run errors) and the findings.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

// Draws one chart as inline SVG markup; `id` is unique on the page (prefix for the SVG's ids).
using ChartRenderer = std::function<std::string(const Plot& plot, const std::string& id)>;

// gnuplot (reports/gnuplot_svg.h) on plot_script(plot), inlined.
ChartRenderer gnuplot_renderer(std::filesystem::path gnuplot);

struct HtmlOptions {
  std::string title = "locbench report";
};

// The whole page. Charts: each report's plots, then histograms of its per-run errors.
std::string html_report(const std::vector<Report>& reports, const ChartRenderer& render,
                        const HtmlOptions& options = {});

// Text made safe inside HTML elements and attribute values.
std::string html_escape(const std::string& text);

}  // namespace locbench::reports
