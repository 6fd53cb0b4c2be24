// Runs the locbench binary as a user would and checks exit codes, outputs and reports.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "datasets/io/carmen_reader.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
using io::read_carmen_log;
namespace {

using testing::Outcome;
using testing::run_locbench;

TEST(Cli, EveryVerbHasHelp) {
  for (const char* verb : {"list", "simulate", "run", "gate", "merge", "report"}) {
    const Outcome o = run_locbench(std::string(verb) + " --help");
    EXPECT_EQ(o.exit_code, 0) << verb;
    EXPECT_NE(o.output.find("Usage"), std::string::npos) << o.output;
  }
}

TEST(Cli, UnknownVerbOrOptionIsAUsageErrorWithExitCode2) {
  EXPECT_EQ(run_locbench("frobnicate").exit_code, 2);
  EXPECT_EQ(run_locbench("run --no-such-option").exit_code, 2);
  EXPECT_EQ(run_locbench("").exit_code, 2);
}

TEST(Cli, RunningAnUnknownExperimentExitsWith2AndSaysSo) {
  const Outcome o = run_locbench("run no/such_experiment");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("no experiment named \"no/such_experiment\""), std::string::npos) << o.output;
}

TEST(Cli, ListNamesTheExperimentsAndScenarios) {
  const Outcome o = run_locbench("list --no-load");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("odometry/sim_corridor"), std::string::npos);
  EXPECT_NE(o.output.find("corridor"), std::string::npos);
  EXPECT_NE(o.output.find("umbmark_trilobot"), std::string::npos);
  // …and every method with where it lives.
  EXPECT_NE(o.output.find("split_and_merge            baselines/laser"), std::string::npos);
  EXPECT_NE(o.output.find("eap                        algorithms/laser"), std::string::npos);
}

TEST(Cli, SimulateWritesALogThatReadsBack) {
  testing::ScratchDir dir;
  const auto log_path = dir.file("corridor.clf.gz");
  const auto tum_path = dir.file("truth.tum");
  const Outcome o =
      run_locbench("simulate corridor --seed 3 -o " + log_path.string() + " --truth-tum " + tum_path.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const Log log = read_carmen_log(log_path);
  EXPECT_GT(log.encoders.size(), 100u);
  EXPECT_GT(log.truth.size(), 10u);
  EXPECT_TRUE(log.nominal_model().has_value());
  EXPECT_TRUE(std::filesystem::exists(tum_path));
}

TEST(Cli, SimulateRejectsAMalformedScenarioFileWithExitCode2) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("bad.json")) << "{\"robot\": {\"no_such_key\": 1}}";
  const Outcome o = run_locbench("simulate " + dir.file("bad.json").string() + " -o " + dir.file("x.clf").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("no_such_key"), std::string::npos) << o.output;
}

TEST(Cli, RunWritesASchemaValidReportForTheSimulatedSmokeExperiment) {
  testing::ScratchDir dir;
  const Outcome o = run_locbench("run odometry/sim_corridor --runs 3 --seed 5 --out " + dir.path().string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto path = dir.file("odometry/sim_corridor.json");
  ASSERT_TRUE(std::filesystem::exists(path)) << o.output;
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto errors = reports::validate_report_json(j);
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(j["seeds"].size(), 3u);
  EXPECT_EQ(j["results"][0]["n"], 3);
  EXPECT_NE(o.output.find("final_position_error"), std::string::npos) << o.output;
}

TEST(Cli, TheSameSeedGivesTheSameResults) {
  testing::ScratchDir dir;
  const std::string args = "run odometry/sim_corridor --runs 2 --seed 11 --out ";
  ASSERT_EQ(run_locbench(args + (dir.path() / "a").string()).exit_code, 0);
  ASSERT_EQ(run_locbench(args + (dir.path() / "b").string()).exit_code, 0);
  const auto a = reports::read_report(dir.path() / "a/odometry/sim_corridor.json");
  const auto b = reports::read_report(dir.path() / "b/odometry/sim_corridor.json");
  ASSERT_EQ(a.body.results.size(), b.body.results.size());
  for (std::size_t i = 0; i < a.body.results.size(); ++i) {
    EXPECT_EQ(a.body.results[i].values, b.body.results[i].values);
  }
}

TEST(Cli, RunOnRealLogsWritesAValidReport) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  testing::ScratchDir dir;
  const Outcome o = run_locbench("run odometry/real_logs --out " + dir.path().string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.file("odometry/real_logs.json"));
  EXPECT_FALSE(r.body.results.empty());
  EXPECT_FALSE(r.body.datasets.empty());
  EXPECT_TRUE(reports::validate_report_json(reports::to_json(r)).empty());
}

TEST(Cli, ABadConfigurationFileExitsWith2) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("c.json")) << "{\"odometry/sim_corridor\": {\"runz\": 3}}";
  const Outcome o = run_locbench("run odometry/sim_corridor --config " + dir.file("c.json").string() + " --out " +
                                 dir.path().string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("runz"), std::string::npos) << o.output;
}

TEST(Cli, GatePassesOnTheBaselineAndFailsWithExitCode1OnAWorsenedResult) {
  testing::ScratchDir dir;
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 3 --out " + (dir.path() / "base").string()).exit_code, 0);
  const std::string base = (dir.path() / "base").string();
  const Outcome same = run_locbench("gate " + base + " --baseline " + base);
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("gate: PASSED"), std::string::npos);

  // Worsen one result fourfold and move its interval, its runs' values, min, max and median with
  // it, as a real regression would (with 3 runs the 95% interval is wide: ± 4.3·s/√3; a mean that
  // contradicts its values is refused as invalid, not judged).
  const auto path = dir.path() / "base/odometry/sim_corridor.json";
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  for (auto& r : j["results"]) {
    if (r["name"] == "odometry_nominal/sim_corridor/final_position_error") {
      const double shift = 3.0 * r["mean"].get<double>();
      r["mean"] = r["mean"].get<double>() + shift;
      r["ci95"][0] = r["ci95"][0].get<double>() + shift;
      r["ci95"][1] = r["ci95"][1].get<double>() + shift;
      for (const char* k : {"min", "max", "median"}) r[k] = r[k].get<double>() + shift;
      for (auto& v : r["values"]) v = v.get<double>() + shift;
    }
  }
  std::filesystem::create_directories(dir.path() / "worse");
  std::ofstream(dir.path() / "worse/sim_corridor.json") << j.dump();
  const Outcome worse =
      run_locbench("gate " + (dir.path() / "worse").string() + " --baseline " + base + " --markdown " +
                   dir.file("gate.md").string() + " --json " + dir.file("gate.json").string());
  EXPECT_EQ(worse.exit_code, 1) << worse.output;
  EXPECT_NE(worse.output.find("regressed"), std::string::npos) << worse.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("gate.md")));
  std::ifstream verdict(dir.file("gate.json"));
  EXPECT_EQ(nlohmann::json::parse(verdict)["passed"], false);
}

TEST(Cli, SetOverridesAFilterOptionAndRejectsAnUnknownOne) {
  testing::ScratchDir dir;
  const Outcome ok = run_locbench(
      "run noise/tables_4_1_4_2 --runs 1 --set "
      "filters.sage_husa_aekf.forgetting=0.95 --out " +
      dir.path().string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const auto r = reports::read_report(dir.file("noise/tables_4_1_4_2.json"));
  EXPECT_EQ(r.body.configuration["filters"]["sage_husa_aekf"]["forgetting"], 0.95);
  const Outcome bad = run_locbench(
      "run noise/tables_4_1_4_2 --runs 1 --set "
      "filters.sage_husa_aekf.forgettin=0.95 --out " +
      dir.path().string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("forgettin"), std::string::npos) << bad.output;
}

TEST(Cli, CalibrateRejectsAMalformedUmbmarkInputWithExitCode2) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("u.json")) << R"({"side_length_m": 1.6})";
  const Outcome o = run_locbench("calibrate umbmark-classic " + dir.file("u.json").string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(run_locbench("calibrate frobnicate x").exit_code, 2);
}

TEST(Cli, CalibrateClassicUmbmarkOnTheExampleWritesAValidReport) {
  testing::ScratchDir dir;
  const Outcome o =
      run_locbench("calibrate umbmark-classic examples/umbmark_trilobot.json --report " + dir.file("c.json").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.file("c.json"));
  EXPECT_TRUE(reports::validate_report_json(reports::to_json(r)).empty());
  bool has_ed = false;
  for (const auto& m : r.body.results) has_ed = has_ed || m.variant == "E_d";
  EXPECT_TRUE(has_ed);
}

TEST(Cli, CalibrateMlJudgesAnImpossibleWheelbaseAsNotIdentifiableAndExits1NeverConverged) {
  testing::ScratchDir dir;
  ASSERT_EQ(run_locbench("simulate corridor --seed 7 -o " + dir.file("c.clf").string()).exit_code, 0);
  const Outcome o =
      run_locbench("calibrate ml " + dir.file("c.clf").string() + " --report " + dir.file("r.json").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_EQ(o.output.find("converged: yes"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("wheelbase = -17.3644 is impossible"), std::string::npos) << o.output;
  const auto r = reports::read_report(dir.file("r.json"));  // written, marked
  for (const auto& m : r.body.results) {
    EXPECT_EQ(m.identifiable, std::optional<bool>(false)) << m.variant;
  }
}

TEST(Cli, CalibrateRefusesAFlagItWouldIgnore) {
  EXPECT_EQ(run_locbench("calibrate ml aces --relations /nonexistent").exit_code, 2);
  EXPECT_EQ(run_locbench("calibrate umbmark-classic examples/umbmark_trilobot.json --relations x").exit_code, 2);
}

TEST(Cli, GateOnMissingInputExitsWith2) {
  EXPECT_EQ(run_locbench("gate /nonexistent --baseline /nonexistent").exit_code, 2);
}

}  // namespace
}  // namespace locbench
