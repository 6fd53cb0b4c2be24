#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "experiment_framework/experiment.h"
#include "tests/benchmarks/experiment_test_support.h"

namespace locbench::experiments {
namespace {

using test_support::find_result;

reports::ExperimentResults run(const std::string& name, int runs, nlohmann::json overrides = {}) {
  const Experiment* e = find_experiment(name);
  if (!e) throw std::runtime_error("no experiment " + name);
  RunOptions o;
  o.seed = 3;
  o.runs = runs;
  nlohmann::json config = e->default_config();
  if (!overrides.is_null()) config = merge_config(config, overrides);
  return e->run(config, o);
}

TEST(CalibrationUmbmarkTrilobot, CalibrationLowersEmaxSystAndPutsTable2_1BesideOurs) {
  const auto r = run("calibration/umbmark_trilobot", 2);
  const double before = find_result(r, "uncalibrated/sim_umbmark_trilobot/e_max_syst").summary.mean;
  const double classic = find_result(r, "umbmark_classic/sim_umbmark_trilobot/e_max_syst").summary.mean;
  const double improved = find_result(r, "umbmark_improved/sim_umbmark_trilobot/e_max_syst").summary.mean;
  EXPECT_GT(before, 0.4);  // hundreds of mm uncalibrated, as in Table 2.1
  EXPECT_LT(classic, 0.6 * before);
  EXPECT_LT(improved, 0.6 * before);
  ASSERT_EQ(r.published.size(), 3u);  // before / UMBmark / improved columns
  EXPECT_EQ(r.published[0].rows[0].published, 670.0);
  EXPECT_TRUE(r.published[0].rows[0].ours.has_value());
  EXPECT_FALSE(r.published[0].note.empty());
}

TEST(CalibrationUmbmarkTrilobot, TheImprovedMethodsEoIsFlaggedNotIdentifiableWithARemedy) {
  const auto r = run("calibration/umbmark_trilobot", 1);
  const auto& e_o = find_result(r, "umbmark_improved/sim_umbmark_trilobot/E_o_error");
  ASSERT_TRUE(e_o.identifiable.has_value());
  EXPECT_FALSE(*e_o.identifiable);
  EXPECT_NE(e_o.note.find("tape"), std::string::npos) << e_o.note;
  const auto& e_d = find_result(r, "umbmark_improved/sim_umbmark_trilobot/E_d_error");
  EXPECT_TRUE(e_d.identifiable.value_or(false));
}

TEST(CalibrationUmbmarkBorenstein, RecoversEdAndEbOfTheFineResolutionRobot) {
  const auto r = run("calibration/umbmark_borenstein", 2);
  // E_d = 1.0025, E_b = 1.01: first-order formulas leave errors of a few 1e-4 and 1e-3.
  EXPECT_LT(std::abs(find_result(r, "umbmark_classic/sim_umbmark_borenstein/E_d_error").summary.mean), 5e-4);
  EXPECT_LT(std::abs(find_result(r, "umbmark_classic/sim_umbmark_borenstein/E_b_error").summary.mean), 4e-3);
  EXPECT_LT(find_result(r, "umbmark_classic/sim_umbmark_borenstein/e_max_syst").summary.mean,
            0.25 * find_result(r, "uncalibrated/sim_umbmark_borenstein/e_max_syst").summary.mean);
}

TEST(CalibrationIdentifiability, TheImprovedEoEstimateDoesNotFollowTheTrueEo) {
  const auto r = run("calibration/identifiability", 2);
  // True E_o = 0.99 and 1.01: the estimate stays ≈ 1, so its error is ≈ ∓0.01 …
  EXPECT_NEAR(find_result(r, "umbmark_improved/E_o_0.99/E_o_error").summary.mean, 0.01, 1e-3);
  EXPECT_NEAR(find_result(r, "umbmark_improved/E_o_1.01/E_o_error").summary.mean, -0.01, 1e-3);
  // … while E_d follows its truth.
  EXPECT_LT(std::abs(find_result(r, "umbmark_improved/E_d_1.005/E_d_error").summary.mean), 1e-3);
}

TEST(NoiseTables, ReportsEveryFilterWithTablesBesideOursAndConsistency) {
  const auto r = run("noise/tables_4_1_4_2", 2);
  for (const char* f : {"fixed_q_ekf", "adaptive_model_ekf", "sage_husa_aekf", "vb_akf"}) {
    const auto& m = find_result(r, std::string(f) + "/sim_corridor/final_position_error");
    EXPECT_EQ(m.summary.n, 2u);
    EXPECT_LT(m.summary.mean, 1.0) << f;  // metres after 10 m
    EXPECT_GT(find_result(r, std::string(f) + "/sim_corridor/nees_time_average").summary.n, 100u);
  }
  ASSERT_EQ(r.published.size(), 3u);
  EXPECT_EQ(r.published[0].rows.size(), 10u);
  EXPECT_EQ(r.published[0].rows[0].published, 64.0);  // AEKF, run 1
}

TEST(QuantizationSigma, PutsTheExactOptimumBesideThePublishedFiveMillimetres) {
  const auto r = run("noise/quantization_sigma", 1);
  EXPECT_NEAR(find_result(r, "quantization_model/c_12_64mm/l2_optimal_sigma").summary.mean, 5.518, 1e-3);
  EXPECT_NEAR(find_result(r, "quantization_model/c_12_64mm/moment_matched_sigma").summary.mean, 12.64 / std::sqrt(6.0),
              1e-9);
  EXPECT_EQ(r.published[0].rows[0].published, 5.00);
}

TEST(NoiseRealLogs, SaysWhatCannotBeEvaluatedAndSkipsAbsentData) {
  const Experiment* e = find_experiment("noise/real_logs");
  ASSERT_NE(e, nullptr);
  const auto r = test_support::run_without_data(*e);
  EXPECT_TRUE(r.results.empty());
  EXPECT_EQ(r.cases.size(), 8u);  // every dataset skipped, none failed
  ASSERT_FALSE(r.notes.empty());  // the reading note comes first, whatever the run found
  EXPECT_NE(r.notes.front().find("none of our real logs has a compass"), std::string::npos);
}

}  // namespace
}  // namespace locbench::experiments
