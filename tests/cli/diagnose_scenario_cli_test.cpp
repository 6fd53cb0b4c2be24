// `locbench diagnose LOG --scenario twin.json` writes the log's extended twin as a scenario that
// `locbench simulate` runs; bad output paths are refused with exit code 2 and touch nothing. The
// report names its input with the checksum of the bytes read.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "core/checksum.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/log_loader.h"
#include "tests/cli/cli_helpers.h"

namespace locbench::testing {
using io::load_log, io::write_carmen_log;
namespace {

namespace fs = std::filesystem;

class DiagnoseScenarioCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("locbench_diagnose_scenario_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    sim::GeneratorOptions o;
    o.velocity_odometry = true;
    o.compass = false;
    o.waypoints = 10;
    log_ = (dir_ / "scaled.clf").string();
    write_carmen_log(sim::generate_log({{"velocity_scale", 0.06}}, 21, o).log, log_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string log_;
};

TEST_F(DiagnoseScenarioCli, WritesTheExtendedTwinWhichSimulateRuns) {
  const std::string scenario = (dir_ / "twin.json").string();
  const Outcome d = run_locbench("diagnose " + log_ + " --scenario " + scenario);
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_NE(d.output.find("twin: velocity_scale"), std::string::npos) << d.output;
  const auto j = read_json(scenario);
  EXPECT_EQ(j["motion"]["kind"], "replay");
  EXPECT_NEAR(j["drive"]["response"]["velocity_scale"].get<double>(), 1.06, 0.01);
  EXPECT_FALSE(fs::exists(scenario + ".tmp"));

  const std::string twin = (dir_ / "twin.clf").string();
  const Outcome s = run_locbench("simulate " + scenario + " -o " + twin);
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const Log real = load_log(log_), sim = load_log(twin);
  EXPECT_EQ(sim.odometry.size(), real.odometry.size());  // the log's odometry, replayed
  EXPECT_GT(sim.truth.size(), 0u);
}

TEST_F(DiagnoseScenarioCli, TheReportRecordsTheInputItReadWithItsChecksum) {
  const std::string report = (dir_ / "diagnosis.json").string();
  const Outcome d = run_locbench("diagnose " + log_ + " --report " + report);
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const auto input = read_json(report).at("input");
  EXPECT_EQ(input.at("name"), log_);
  EXPECT_EQ(input.at("path"), log_);
  EXPECT_EQ(input.at("checksum"), file_checksum(log_));
  EXPECT_EQ(input.at("records").get<std::size_t>(), load_log(log_).record_count());
  EXPECT_GT(input.at("duration_s").get<double>(), 0.0);

  const std::string histogram = "examples/table_3_1_histogram.json";
  const Outcome h = run_locbench("diagnose " + histogram + " --report " + report);
  ASSERT_EQ(h.exit_code, 0) << h.output;
  EXPECT_EQ(read_json(report).at("input").at("checksum"), file_checksum(histogram));
}

TEST_F(DiagnoseScenarioCli, RefusesToOverwriteItsInputOrWriteWhereItCannot) {
  const auto before = fs::file_size(log_);
  const Outcome same = run_locbench("diagnose " + log_ + " --scenario " + log_);
  EXPECT_EQ(same.exit_code, 2) << same.output;
  EXPECT_NE(same.output.find("would overwrite the input"), std::string::npos) << same.output;
  EXPECT_EQ(fs::file_size(log_), before);

  const Outcome report_same = run_locbench("diagnose " + log_ + " --report " + log_);
  EXPECT_EQ(report_same.exit_code, 2) << report_same.output;
  EXPECT_EQ(fs::file_size(log_), before);

  // A folder that cannot exist (its parent is the log, a file): exit 2, nothing written.
  const std::string nowhere = (fs::path(log_) / "twin.json").string();
  const Outcome missing = run_locbench("diagnose " + log_ + " --scenario " + nowhere);
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("cannot create the folder"), std::string::npos) << missing.output;
  EXPECT_EQ(fs::file_size(log_), before);

  const Outcome histogram =
      run_locbench("diagnose examples/table_3_1_histogram.json --scenario " + (dir_ / "h.json").string());
  EXPECT_EQ(histogram.exit_code, 2) << histogram.output;
  EXPECT_NE(histogram.output.find("no motion to replay"), std::string::npos) << histogram.output;
}

}  // namespace
}  // namespace locbench::testing
