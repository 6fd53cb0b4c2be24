#include "reports/charts.h"

#include <gtest/gtest.h>

namespace locbench::reports {
namespace {

TEST(Histogram, CountsEverySampleOnceInEqualBinsOverThePooledRange) {
  // Pooled range [0, 4], 4 bins of width 1: 4.0 goes into the last bin.
  const Histogram h = histogram({{0.0, 0.5, 1.5, 4.0}, {2.0, 2.5, 3.9}}, 4);
  EXPECT_DOUBLE_EQ(h.low, 0.0);
  EXPECT_DOUBLE_EQ(h.width, 1.0);
  EXPECT_EQ(h.counts[0], (std::vector<int>{2, 1, 0, 1}));
  EXPECT_EQ(h.counts[1], (std::vector<int>{0, 0, 2, 1}));
}

TEST(Histogram, LeavesOutNonFiniteSamplesAndSurvivesAConstantSample) {
  const Histogram h = histogram({{1.0, 1.0, std::numeric_limits<double>::quiet_NaN()}}, 5);
  EXPECT_GT(h.width, 0.0);
  int total = 0;
  for (int c : h.counts[0]) total += c;
  EXPECT_EQ(total, 2);
}

TEST(EmpiricalCdf, StepsUpByOneOverNAtEachSortedValue) {
  const CdfSteps c = empirical_cdf({3.0, 1.0, std::numeric_limits<double>::quiet_NaN(), 2.0, 4.0});
  EXPECT_EQ(c.x, (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
  EXPECT_EQ(c.y, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  std::vector<double> many;
  for (int i = 0; i < 1001; ++i) many.push_back(i);
  const CdfSteps thin = empirical_cdf(many, 100);
  EXPECT_LE(thin.x.size(), 101u);
  EXPECT_DOUBLE_EQ(thin.x.back(), 1000.0);  // the last corner is always kept
  EXPECT_DOUBLE_EQ(thin.y.back(), 1.0);
  EXPECT_TRUE(empirical_cdf({}).x.empty());
}

TEST(PlotScript, DrawsACdfChartAsOneStepLinePerSample) {
  Plot p;
  p.kind = "cdf";
  p.title = "x residual";
  p.series = {{"real log", {}, {0.1, -0.2, 0.3}}, {"nominal twin", {}, {0.0, 0.5}}, {"extended twin", {}, {0.2}}};
  const std::string s = plot_script(p);
  EXPECT_NE(s.find("set yrange [0:1]"), std::string::npos);
  EXPECT_NE(s.find("with steps"), std::string::npos);
  EXPECT_NE(s.find("-0.2 0.333333333"), std::string::npos) << s;  // the first corner of the real CDF
  EXPECT_NE(s.find("title 'extended twin'"), std::string::npos);
}

TEST(PlotScript, DrawsAScanPairToScaleWithPointsAndSeparateSegments) {
  Plot p;
  p.kind = "scan_pair";
  p.title = "relation";
  p.series = {{"first scan", {1.0, 2.0}, {0.5, 0.5}},
              {"first-scan lines", {0.0, 3.0, 3.0, 3.0}, {0.0, 0.0, 0.0, 2.0}},
              {"EAP matches", {1.0, 1.0}, {0.52, 0.5}}};
  const std::string s = plot_script(p);
  EXPECT_NE(s.find("set size ratio -1"), std::string::npos);  // metres to scale
  EXPECT_NE(s.find("$s0 using 1:2 with points"), std::string::npos) << s;
  EXPECT_NE(s.find("$s1 using 1:2 with lines"), std::string::npos) << s;
  EXPECT_NE(s.find("$s2 using 1:2 with lines"), std::string::npos) << s;
  // Two wall segments: a blank line after each pair, so gnuplot does not join (3, 0) to (3, 0).
  EXPECT_NE(s.find("0 0\n3 0\n\n3 0\n3 2\n\n"), std::string::npos) << s;
  EXPECT_TRUE(is_segment_series("eap_iterated_pl matches"));
  EXPECT_FALSE(is_segment_series("second scan at odometry"));
}

TEST(MetricHistograms, DrawsErrorsOverMonteCarloRunsGroupedByDatasetAndVariant) {
  ExperimentResults r;
  const std::vector<double> five{1, 2, 3, 4, 5};
  r.results.push_back(make_metric("a", "sim", "final_position_error", "m", "monte_carlo_runs", five));
  r.results.push_back(make_metric("b", "sim", "final_position_error", "m", "monte_carlo_runs", five));
  r.results.push_back(make_metric("a", "sim", "nees_time_average", "", "time_steps", five));
  r.results.push_back(
      make_metric("a", "sim", "ape_rmse_error", "m", "monte_carlo_runs", std::vector<double>{1, 2}));  // too few values
  const auto plots = metric_histograms(r);
  ASSERT_EQ(plots.size(), 1u);
  EXPECT_EQ(plots[0].kind, "histogram");
  ASSERT_EQ(plots[0].series.size(), 2u);
  EXPECT_EQ(plots[0].series[1].name, "b");
  EXPECT_EQ(plots[0].series[1].y, five);
  EXPECT_EQ(plots[0].x_unit, "m");
}

Plot trajectory(double width, double height) {
  return {"t",       "trajectory",
          "title's", "x",
          "m",       "y",
          "m",       {{"truth", {0, width}, {0, height}}, {"odometry_nominal", {0, width}, {0, 0.9 * height}}},
          ""};
}

TEST(PlotScript, WritesEachSeriesAsADatablockWithPlainTextTitles) {
  const std::string s = plot_script(trajectory(2.0, 1.0));
  EXPECT_NE(s.find("set terminal svg"), std::string::npos);
  EXPECT_NE(s.find("noenhanced"), std::string::npos);  // "odometry_nominal" keeps its underscore
  EXPECT_NE(s.find("$s0 << EOD\n0 0\n2 1\nEOD"), std::string::npos) << s;
  EXPECT_NE(s.find("title 'odometry_nominal'"), std::string::npos);
  EXPECT_NE(s.find("set title 'title''s'"), std::string::npos) << s;  // quote doubled
  EXPECT_NE(s.find("set xlabel 'x [m]'"), std::string::npos);
}

TEST(PlotScript, DrawsAPlaneTrajectoryToScaleButNotACorridor) {
  EXPECT_NE(plot_script(trajectory(2.0, 1.0)).find("set size ratio -1"), std::string::npos);
  EXPECT_EQ(plot_script(trajectory(10.0, 0.3)).find("set size ratio -1"), std::string::npos);
}

TEST(SamplePlot, KeepsKindLabelsSamplesAndNoteAndLeavesTheYUnitEmpty) {
  const Plot p =
      sample_plot("cdf", "fraction of samples", "c", "errors", "final error", "mm", {{"a", {}, {3.0, 1.0}}}, "run 0");
  EXPECT_EQ(p.kind, "cdf");
  EXPECT_EQ(p.y_label, "fraction of samples");
  EXPECT_EQ(p.y_unit, "");
  EXPECT_EQ(p.name, "c");
  EXPECT_EQ(p.title, "errors");
  EXPECT_EQ(p.x_label, "final error");
  EXPECT_EQ(p.x_unit, "mm");
  ASSERT_EQ(p.series.size(), 1u);
  EXPECT_EQ(p.series[0].y, (std::vector<double>{3.0, 1.0}));
  EXPECT_EQ(p.note, "run 0");
  const Plot h = histogram_plot("h", "errors", "final error", "m", {}, "");
  EXPECT_EQ(h.kind, "histogram");
  EXPECT_EQ(h.y_label, "runs");
}

TEST(PlotScript, DrawsAHistogramAsBoxesOfTheBinnedCounts) {
  const Plot p = histogram_plot("h", "errors", "final error", "m", {{"a", {}, {0.0, 0.0, 1.0, 1.0, 1.0}}}, "");
  const std::string s = plot_script(p);
  EXPECT_NE(s.find("with boxes"), std::string::npos);
  EXPECT_NE(s.find("set boxwidth 0.2 absolute"), std::string::npos) << s;  // 5 bins over [0, 1]
  EXPECT_NE(s.find("0.1 2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("0.9 3\n"), std::string::npos) << s;
}

}  // namespace
}  // namespace locbench::reports
