// diagnosis/sim_to_real: without data it says so; with MRCLAM robot 2 (skipped when absent) it
// compares the log with both twins and its nominal floor agrees with the diagnosis's own fit.
#include <gtest/gtest.h>

#include <filesystem>

#include "experiment_framework/experiment.h"
#include "tests/benchmarks/experiment_test_support.h"

namespace locbench::experiments {
namespace {

const reports::MetricResult& find(const reports::ExperimentResults& r, const std::string& name) {
  for (const auto& m : r.results) {
    if (m.name() == name) return m;
  }
  ADD_FAILURE() << "no result " << name;
  static reports::MetricResult none;
  return none;
}

TEST(DiagnosisSimToReal, SaysPlainlyWhenNoRealLogIsThere) {
  const Experiment* e = find_experiment("diagnosis/sim_to_real");
  ASSERT_NE(e, nullptr);
  EXPECT_TRUE(e->in_default_suite());
  const auto r = test_support::run_without_data(*e);
  EXPECT_TRUE(r.results.empty());
  EXPECT_EQ(r.cases.size(), 8u);
  for (const auto& c : r.cases) EXPECT_EQ(c.status, "skipped") << c.name;
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("No real log was found"), std::string::npos);
}

TEST(DiagnosisSimToReal, ComparesMrclamRobot2WithBothTwins) {
  const char* root = std::getenv("LOCBENCH_DATA");
  if (!root || !std::filesystem::exists(std::filesystem::path(root) / "mrclam/MRCLAM_Dataset6")) {
    GTEST_SKIP() << "MRCLAM Dataset 6 not found under $LOCBENCH_DATA";
  }
  const Experiment* e = find_experiment("diagnosis/sim_to_real");
  RunOptions o;
  o.data_root = root;
  auto config = e->default_config();
  config["datasets"] = {"mrclam6_robot2"};
  config["span_s"] = 120.0;
  config["twin_runs"] = 1;
  const auto r = e->run(config, o);
  ASSERT_TRUE(r.cases.empty()) << r.cases.front().reason;
  for (const char* c : {"x", "y", "theta"}) {
    for (const char* w : {"1s", "10s"}) {
      const double dn = find(r, std::string("nominal_twin/mrclam6_robot2/ks_distance_") + w + "_" + c).summary.mean;
      const double de = find(r, std::string("extended_twin/mrclam6_robot2/ks_distance_") + w + "_" + c).summary.mean;
      EXPECT_GT(dn, 0.0);
      EXPECT_LE(dn, 1.0);
      EXPECT_NEAR(
          find(r, std::string("extended_vs_nominal/mrclam6_robot2/ks_distance_ratio_") + w + "_" + c).summary.mean,
          de / dn, 1e-12);
    }
    // Two estimates of the nominal model's noise floor, made two ways, agree within 25%.
    const double twin = find(r, std::string("nominal_twin/mrclam6_robot2/noise_floor_sigma_") + c).summary.mean;
    const double ml = find(r, std::string("diagnosis_ml/mrclam6_robot2/noise_floor_sigma_") + c).summary.mean;
    EXPECT_NEAR(twin / ml, 1.0, 0.25) << c << ": moment-matched " << twin << ", diagnosis " << ml;
  }
  ASSERT_EQ(r.plots.size(), 3u);  // one CDF chart per component (1 s windows)
  EXPECT_EQ(r.plots[0].kind, "cdf");
  EXPECT_EQ(r.plots[0].series.size(), 3u);
  EXPECT_NE(r.notes.back().find("MRCLAM"), std::string::npos);  // the goal, met or not, said plainly
}

}  // namespace
}  // namespace locbench::experiments
