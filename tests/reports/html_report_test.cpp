#include "reports/html_report.h"

#include <gtest/gtest.h>

#include "reports/gnuplot_svg.h"
#include "tests/reports/sample_report.h"

namespace locbench::reports {
namespace {

// Stands in for gnuplot: records what it was asked to draw.
struct StubRenderer {
  std::vector<std::string> drawn;
  ChartRenderer renderer() {
    return [this](const Plot& p, const std::string& id) {
      drawn.push_back(p.kind + ":" + p.name);
      return "<svg id='" + id + "'><path d='M0,0 L1,1'/></svg>";
    };
  }
};

Report report_with_chart() {
  Report r = testing::sample_report();
  r.body.notes.push_back("a <finding> & its reason");
  r.body.plots.push_back(
      {"trajectories_run_0", "trajectory", "Trajectories", "x", "m", "y", "m", {{"truth", {0, 1}, {0, 1}}}, "run 0"});
  r.body.results.push_back(make_metric("odometry_nominal", "sim_corridor", "ape_rmse_error", "m", "monte_carlo_runs",
                                       std::vector<double>{1, 2, 3, 4, 5}));
  return r;
}

// The page of the sample report, charts drawn by the stub.
std::string sample_page() {
  StubRenderer stub;
  return html_report({testing::sample_report()}, stub.renderer());
}

// Expects the page of the sample report to hold each of `parts`, and prints the page when one is missing.
void expect_sample_page_holds(const std::vector<std::string>& parts) {
  const std::string h = sample_page();
  for (const auto& part : parts) EXPECT_NE(h.find(part), std::string::npos) << "no \"" << part << "\" in:\n" << h;
}

TEST(HtmlReport, IsOneSelfContainedPageWithoutScriptOrExternalResources) {
  StubRenderer stub;
  const std::string h = html_report({report_with_chart()}, stub.renderer());
  EXPECT_EQ(h.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(h.find("<script"), std::string::npos);
  EXPECT_EQ(h.find("http://"), std::string::npos);
  EXPECT_EQ(h.find("https://"), std::string::npos);
  EXPECT_EQ(h.find("src="), std::string::npos);
}

TEST(HtmlReport, ShowsMeanWithIts95PercentIntervalPerMetricAndMethod) {
  // values 0.10, 0.12, 0.08: mean 0.1, s = 0.02, t(0.975, 2) = 4.303 → ± 0.04968.
  expect_sample_page_holds(
      {"<td>final_position_error</td><td>odometry_nominal</td><td>sim_corridor</td>"
       "<td class=n>0.1 ± 0.04968 m</td>"});
}

TEST(HtmlReport, PutsPublishedBesideOursWithTheDifference) {
  // 512.3 − 580 = −67.7; 512.3 / 580 = 0.8833.
  expect_sample_page_holds({"Published vs ours: thesis Table 3.2 — final error [mm]",
                            "<td>run 1</td><td class=n>580</td><td class=n>512.3</td><td class=n>-67.7</td>"
                            "<td class=n>0.8833</td>",
                            "<td>run 2</td><td class=n>551</td><td class=n>—</td>"});
}

TEST(HtmlReport, ListsEstimatesWithIntervalsAndSaysWhichAreNotIdentifiable) {
  expect_sample_page_holds({"<h3>Estimates</h3>",
                            "<span class=bad>not identifiable</span></td><td class=note>only E_o/E_b is "
                            "determined by the square</td>"});
}

TEST(HtmlReport, DrawsTheReportsPlotsThenHistogramsOfPerRunErrors) {
  StubRenderer stub;
  const std::string h = html_report({report_with_chart()}, stub.renderer());
  ASSERT_EQ(stub.drawn.size(), 2u);
  EXPECT_EQ(stub.drawn[0], "trajectory:trajectories_run_0");
  EXPECT_EQ(stub.drawn[1], "histogram:histogram_sim_corridor_ape_rmse_error");
  EXPECT_NE(h.find("<figure class=chart id=\"chart1\" data-kind=\"trajectory\">"), std::string::npos);
  EXPECT_NE(h.find("<svg id='chart2'>"), std::string::npos);
}

TEST(HtmlReport, FindingsShowHowWellEachTwinForecastsTheRealResults) {
  Report r = testing::sample_report();
  r.body.results.push_back(
      make_estimate("nominal_twin", "all_logs", "position_rmse_covered_fraction", "", 0.14, 0, 35));
  r.body.results.push_back(
      make_estimate("extended_twin", "all_logs", "position_rmse_covered_fraction", "", 0.49, 0, 35));
  r.body.results.push_back(make_estimate("nominal_twin", "all_logs", "position_rmse_mmrv", "", 0.339, 0, 32));
  r.body.results.push_back(make_estimate("extended_twin", "all_logs", "position_rmse_mmrv", "", 0.057, 0, 32));
  r.body.results.push_back(
      make_estimate("extended_twin", "all_logs", "position_rmse_misses_of_the_motion_model", "", 2, 0, 35));
  r.body.results.push_back(
      make_estimate("extended_twin", "all_logs", "position_rmse_misses_of_the_sensor_model", "", 1, 0, 35));
  StubRenderer stub;
  const std::string h = html_report({r}, stub.renderer());
  EXPECT_NE(h.find("Twins: does the simulator forecast the real result?"), std::string::npos);
  EXPECT_NE(h.find("<td>position_rmse</td><td>14% / 49%</td><td>—</td><td>0.339 / 0.057</td><td>2 / 1</td>"),
            std::string::npos)
      << "covered, Pearson (not reported), MMRV: nominal / extended; the extended twin's misses: motion / sensor";
  EXPECT_EQ(sample_page().find("findings-twins"), std::string::npos) << "no twin results, no table";
}

TEST(HtmlReport, EscapesTextFromReports) {
  StubRenderer stub;
  const std::string h = html_report({report_with_chart()}, stub.renderer());
  EXPECT_NE(h.find("<li>a &lt;finding&gt; &amp; its reason</li>"), std::string::npos);
  EXPECT_EQ(h.find("<finding>"), std::string::npos);
}

TEST(InlineSvg, DropsTheXmlPrologAndMakesIdsAndTheirReferencesUnique) {
  const std::string svg =
      "<?xml version=\"1.0\"?>\n<svg><defs><path id='gpPt0' d='M0,0'/>"
      "<filter id=\"textbox\"/></defs><use xlink:href='#gpPt0'/><g filter=\"url(#textbox)\"/></svg>";
  const std::string s = inline_svg(svg, "chart7-");
  EXPECT_EQ(s.rfind("<svg>", 0), 0u);
  EXPECT_NE(s.find("id='chart7-gpPt0'"), std::string::npos) << s;
  EXPECT_NE(s.find("xlink:href='#chart7-gpPt0'"), std::string::npos) << s;
  EXPECT_NE(s.find("id=\"chart7-textbox\""), std::string::npos) << s;
  EXPECT_NE(s.find("url(#chart7-textbox)"), std::string::npos) << s;
  EXPECT_EQ(s.find("'#gpPt0'"), std::string::npos);
}

TEST(Gnuplot, DrawsAPlotAsAnSvgWithPlottedPaths) {
  const auto gnuplot = find_gnuplot();
  if (!gnuplot) GTEST_SKIP() << "gnuplot not installed (scripts/setup.sh installs gnuplot-nox)";
  StubRenderer unused;
  const std::string svg = gnuplot_renderer(*gnuplot)(report_with_chart().body.plots[0], "c1");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("<path"), std::string::npos);
  EXPECT_NE(svg.find("id=\"c1-gnuplot_canvas\""), std::string::npos);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
}

}  // namespace
}  // namespace locbench::reports
