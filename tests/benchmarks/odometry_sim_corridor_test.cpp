#include <gtest/gtest.h>

#include "experiment_framework/experiment.h"
#include "tests/benchmarks/experiment_test_support.h"

namespace locbench::experiments {
namespace {

using test_support::find_result;

reports::ExperimentResults run_corridor(const nlohmann::json& overrides, int runs, std::uint64_t seed) {
  const Experiment* e = find_experiment("odometry/sim_corridor");
  RunOptions o;
  o.seed = seed;
  o.runs = runs;
  return e->run(merge_config(e->default_config(), overrides), o);
}

TEST(OdometrySimCorridor, ReportsEveryRunWithItsSeed) {
  const auto r = run_corridor(nlohmann::json::object(), 3, 1);
  EXPECT_EQ(r.seeds.size(), 3u);
  const auto& m = find_result(r, "odometry_nominal/sim_corridor/final_position_error");
  EXPECT_EQ(m.summary.n, 3u);
  EXPECT_EQ(m.values.size(), 3u);
  EXPECT_LE(m.summary.ci95_low, m.summary.mean);
  EXPECT_GE(m.summary.ci95_high, m.summary.mean);
  ASSERT_EQ(r.datasets.size(), 1u);
  EXPECT_EQ(r.datasets[0].path, "simulated");
}

TEST(OdometrySimCorridor, NoiseFreeRobotWithExactModelHasNoDeadReckoningError) {
  // No floor noise, no slip, no sampling jitter, nominal = actual: what is left is the
  // sub-tick quantization of the cumulative counts.
  const nlohmann::json quiet = {
      {"scenario",
       {{"floor", {{"k_left", 0.0}, {"k_right", 0.0}}},
        {"encoders", {{"jitter", 0.0}}},
        {"slip", {{"straight", {{"rate", 0.0}}}, {"turn", {{"rate", 0.0}}}}},
        {"robot", {{"actual", {{"diameter_left", 0.0885}, {"diameter_right", 0.08893}, {"wheelbase", 0.19793}}}}}}}};
  const auto r = run_corridor(quiet, 2, 4);
  // One tick is 12.6 mm; the end pose is off by less than a tick and a hair of heading.
  EXPECT_LT(find_result(r, "odometry_nominal/sim_corridor/final_position_error").summary.max, 0.0127);
  EXPECT_LT(find_result(r, "odometry_nominal/sim_corridor/final_heading_error").summary.max, 0.0127 / 0.19793);
}

TEST(OdometrySimCorridor, AWrongNominalWheelDiameterShowsAsSystematicError) {
  // Nominal right wheel 2% small: the robot believes it curves; the true geometry does not.
  const nlohmann::json wrong = {{"scenario",
                                 {{"floor", {{"k_left", 0.0}, {"k_right", 0.0}}},
                                  {"slip", {{"straight", {{"rate", 0.0}}}, {"turn", {{"rate", 0.0}}}}},
                                  {"robot", {{"nominal", {{"diameter_right", 0.0885 * 0.98}}}}}}}};
  const auto r = run_corridor(wrong, 2, 4);
  const double nominal = find_result(r, "odometry_nominal/sim_corridor/final_position_error").summary.mean;
  const double truth = find_result(r, "odometry_true_geometry/sim_corridor/final_position_error").summary.mean;
  EXPECT_GT(nominal, 1.0);  // metres off after 10 m
  EXPECT_LT(truth, 0.05);
}

}  // namespace
}  // namespace locbench::experiments
