// `locbench localize`: the global-localization baselines and the Kalman trackers over a log.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "reports/schema_validation.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::Outcome;
using testing::run_locbench;

std::string room_map() { return std::string(LOCBENCH_SOURCE_DIR) + "/examples/room_map.json"; }

double result(const nlohmann::json& report, const std::string& variant) {
  for (const auto& r : report.at("results")) {
    if (r.at("variant") == variant) return r.at("mean").get<double>();
  }
  ADD_FAILURE() << "no result " << variant;
  return 0.0;
}

TEST(LocalizeCli, MclAndTheEkfLocalizeASimulatedRoomLogAndWriteValidReports) {
  testing::ScratchDir dir;
  const std::string log = dir.file("room.clf").string();
  ASSERT_EQ(run_locbench("simulate room_laser --seed 2 -o " + log).exit_code, 0);
  for (const std::string method : {"mcl", "ekf"}) {
    const std::string report = dir.file(method + ".json").string(), tum = dir.file(method + ".tum").string();
    const Outcome o = run_locbench("localize --method " + method + " --map " + room_map() + " --log " + log +
                                   " --seed 3 --report " + report + " --tum " + tum);
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const auto j = testing::read_json(report);
    EXPECT_TRUE(reports::validate_report_json(j).empty());
    // Scored against the log's TRUEPOS: MCL from an unknown start, the EKF from the true start.
    EXPECT_LT(result(j, "position_error"), method == "mcl" ? 0.3 : 0.05) << method;
    std::ifstream in(tum);
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) lines += !line.empty() && line[0] != '#';
    EXPECT_EQ(lines, 299) << method;
  }
}

TEST(LocalizeCli, BadInputIsAClearErrorWithExitCode2) {
  testing::ScratchDir dir;
  const std::string log = dir.file("room.clf").string();
  ASSERT_EQ(run_locbench("simulate room_laser --seed 2 -o " + log).exit_code, 0);
  Outcome o = run_locbench("localize --method teleport --map " + room_map() + " --log " + log);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("unknown localization method"), std::string::npos) << o.output;
  o = run_locbench("localize --log " + log);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("--map"), std::string::npos) << o.output;
  o = run_locbench("localize --method ekf --map " + room_map() + " --log " + log + " --start 1,2");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("X,Y,THETA"), std::string::npos) << o.output;
  const std::string opts = dir.file("opts.json").string();
  std::ofstream(opts) << R"({"mcl": {"particles": 10}})";
  o = run_locbench("localize --map " + room_map() + " --log " + log + " --options " + opts);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("particles"), std::string::npos) << o.output;
  const std::string corridor = dir.file("corridor.clf").string();
  ASSERT_EQ(run_locbench("simulate corridor -o " + corridor).exit_code, 0);
  o = run_locbench("localize --map " + room_map() + " --log " + corridor);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("laser scans"), std::string::npos) << o.output;
}

TEST(LocalizeCli, MapFromTheLogsOwnScansOnARealFreiburgLog) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/mit-csail.clf.gz");
  const std::string log = (catalog::data_root() / "slam_benchmark/clf/mit-csail.clf.gz").string();
  testing::ScratchDir dir;
  const std::string report = dir.file("mit.json").string();
  const Outcome o = run_locbench("localize --method mcl --map-from-log 60 --log " + log + " --report " + report);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = testing::read_json(report);
  EXPECT_TRUE(reports::validate_report_json(j).empty());
  EXPECT_GT(result(j, "memory"), 0.0);
}

}  // namespace
}  // namespace locbench
