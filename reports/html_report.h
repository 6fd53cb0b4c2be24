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

// Draws every chart of the page at once (ids[i] for plots[i]); one gnuplot run for the page.
using ChartBatchRenderer =
    std::function<std::vector<std::string>(const std::vector<Plot>& plots, const std::vector<std::string>& ids)>;

// gnuplot (reports/gnuplot_svg.h) on plot_script(plot), inlined.
ChartRenderer gnuplot_renderer(std::filesystem::path gnuplot);
// The same for all charts in one gnuplot process (run_gnuplot_batch): the page's charts cost one
// process start instead of one each.
ChartBatchRenderer gnuplot_batch_renderer(std::filesystem::path gnuplot);

struct HtmlOptions {
  std::string title = "locbench report";
};

// The whole page: first the findings (reports/findings.h: each published table with a stated
// tolerance, its claim, our measurement and the verdict; each diagnosed log's kept causes with
// their 95% intervals and held-out gains), then the index of experiments, then per experiment its
// tables and charts (its plots, then histograms of its per-run errors).
std::string html_report(const std::vector<Report>& reports, const ChartBatchRenderer& render,
                        const HtmlOptions& options = {});
std::string html_report(const std::vector<Report>& reports, const ChartRenderer& render,
                        const HtmlOptions& options = {});

// Text made safe inside HTML elements and attribute values.
std::string html_escape(const std::string& text);

}  // namespace locbench::reports
