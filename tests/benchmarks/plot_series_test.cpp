#include "experiment_framework/plot_series.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "experiment_framework/experiment.h"

namespace locbench::experiments {
namespace {

// Straight along x at 1 m/s for 4 s, poses every second.
Trajectory straight(double y_offset_per_metre) {
  Trajectory t;
  for (int i = 0; i <= 4; ++i) t.push_back({double(i), {double(i), y_offset_per_metre * i, 0.0}});
  return t;
}

TEST(DistanceGrid, StepsFromZeroUpToTheTotal) {
  EXPECT_EQ(distance_grid(1.0, 0.25), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_TRUE(distance_grid(1.0, 0.0).empty());
}

TEST(ErrorAtDistances, IsTheOffsetWhereTheTruthHasTravelledEachDistance) {
  // The estimate drifts 0.1 m sideways per metre: at 2 m the error is 0.2 m.
  const auto e = error_at_distances(straight(0.0), straight(0.1), {0.0, 2.0, 3.5, 9.0});
  EXPECT_DOUBLE_EQ(e[0], 0.0);
  EXPECT_NEAR(e[1], 0.2, 1e-12);
  EXPECT_NEAR(e[2], 0.4, 1e-12);  // first true pose at or past 3.5 m is at 4 m
  EXPECT_TRUE(std::isnan(e[3]));  // the truth never gets to 9 m
}

TEST(MeanOverRuns, AveragesTheFiniteValuesAndDropsPointsNoRunReached) {
  const double nan = std::nan("");
  const auto s = mean_over_runs("m", {0.0, 1.0, 2.0}, {{0.0, 1.0, nan}, {0.0, 3.0}});
  EXPECT_EQ(s.x, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(s.y, (std::vector<double>{0.0, 2.0}));
}

TEST(TrajectorySeries, ThinsLongPathsButKeepsTheEnds) {
  Trajectory t;
  for (int i = 0; i < 1000; ++i) t.push_back({double(i), {double(i), 0.0, 0.0}});
  const auto s = trajectory_series("truth", t, 100);
  EXPECT_LE(s.x.size(), 101u);
  EXPECT_EQ(s.x.front(), 0.0);
  EXPECT_EQ(s.x.back(), 999.0);
}

TEST(CdfSamples, KeepsEvenlySpacedOrderStatisticsWithBothEnds) {
  std::vector<double> v;
  for (int i = 1000; i >= 0; --i) v.push_back(double(i));  // 0…1000, reversed
  v.push_back(std::nan(""));
  const auto s = cdf_samples("m", v, 11);
  ASSERT_EQ(s.y.size(), 11u);
  EXPECT_EQ(s.y.front(), 0.0);
  EXPECT_EQ(s.y[5], 500.0);
  EXPECT_EQ(s.y.back(), 1000.0);
  EXPECT_EQ(cdf_samples("m", {3.0, 1.0, 2.0}, 11).y, (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(BinnedMeans, AveragesEqualCountBinsAlongX) {
  // y = 2x on x = 0…11: 3 bins of 4 → means x 1.5, 5.5, 9.5 and y 3, 11, 19.
  std::vector<double> x, y;
  for (int i = 11; i >= 0; --i) {
    x.push_back(i);
    y.push_back(2.0 * i);
  }
  const auto s = binned_means("b", x, y, 3);
  EXPECT_EQ(s.x, (std::vector<double>{1.5, 5.5, 9.5}));
  EXPECT_EQ(s.y, (std::vector<double>{3.0, 11.0, 19.0}));
}

// The experiment's results with its default configuration and `runs` Monte-Carlo runs.
reports::ExperimentResults run_with_defaults(const std::string& name, int runs) {
  const Experiment* e = find_experiment(name);
  RunOptions o;
  o.runs = runs;
  return e->run(e->default_config(), o);
}

const reports::Plot& plot(const reports::ExperimentResults& r, const std::string& name) {
  for (const auto& p : r.plots) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no plot " + name);
}

std::vector<std::string> series_names(const reports::Plot& p) {
  std::vector<std::string> names;
  for (const auto& s : p.series) names.push_back(s.name);
  return names;
}

TEST(ExperimentPlots, CorridorDrawsRunZerosTrajectoriesAndErrorAgainstDistance) {
  const auto r = run_with_defaults("odometry/sim_corridor", 2);
  const auto& traj = plot(r, "trajectories_run_0");
  ASSERT_THAT(series_names(traj), ::testing::ElementsAre("truth", "odometry_nominal", ::testing::_));
  // The corridor is 10 m long: the truth ends near x = 10 m.
  EXPECT_NEAR(traj.series[0].x.back() - traj.series[0].x.front(), 10.0, 0.5);
  const auto& dist = plot(r, "error_vs_distance");
  ASSERT_EQ(dist.series.size(), 2u);
  EXPECT_EQ(dist.series[0].x.front(), 0.0);
  EXPECT_GT(dist.series[0].x.back(), 9.0);
  // The last point is (close to) the mean final position error.
  double final_mean = 0.0;
  for (const auto& m : r.results) {
    if (m.name() == "odometry_nominal/sim_corridor/final_position_error") final_mean = m.summary.mean;
  }
  EXPECT_NEAR(dist.series[0].y.back(), final_mean, 0.25 * final_mean + 0.02);
}

TEST(ExperimentPlots, NoiseTablesDrawTruthOdometryAndTheFourFilters) {
  const auto r = run_with_defaults("noise/tables_4_1_4_2", 1);
  EXPECT_THAT(series_names(plot(r, "trajectories_run_0")),
              ::testing::ElementsAre("truth", "odometry_nominal", ::testing::_, ::testing::_, ::testing::_, "vb_akf"));
  EXPECT_EQ(plot(r, "error_vs_distance").series.size(), 5u);
}

}  // namespace
}  // namespace locbench::experiments
