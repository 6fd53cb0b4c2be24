// `locbench match`: a user's log and line map → per-scan matching and correction report.
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

TEST(MatchCli, MatchesEveryScanOfASimulatedRoomLogAndWritesAValidReportAndTum) {
  testing::ScratchDir dir;
  const std::string log = dir.file("room.clf").string();
  ASSERT_EQ(run_locbench("simulate room_laser --seed 2 -o " + log).exit_code, 0);
  const std::string report = dir.file("match.json").string(), tum = dir.file("c.tum").string();
  const Outcome o =
      run_locbench("match --map " + room_map() + " --log " + log + " --report " + report + " --tum " + tum);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = testing::read_json(report);
  EXPECT_TRUE(reports::validate_report_json(j).empty());
  for (const auto& r : j.at("results")) {
    if (r.at("variant") == "segments_matched") {
      EXPECT_EQ(r.at("n"), 299);  // every FLASER scan of the 60 s run
      EXPECT_GT(r.at("mean").get<double>(), 3.0);
    }
    if (r.at("variant") == "position_fixed_fraction") {
      EXPECT_GT(r.at("mean").get<double>(), 0.5);
    }
  }
  std::ifstream in(tum);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) lines += !line.empty() && line[0] != '#';  // poses, not header
  EXPECT_EQ(lines, 299);
}

TEST(MatchCli, BadMapOrALogWithoutScansIsAClearErrorWithExitCode2) {
  testing::ScratchDir dir;
  const std::string bad = dir.file("bad.json").string();
  std::ofstream(bad) << R"({"segments": [[0, 0, 1]]})";
  const std::string log = dir.file("corridor.clf").string();
  ASSERT_EQ(run_locbench("simulate corridor -o " + log).exit_code, 0);
  Outcome o = run_locbench("match --map " + bad + " --log " + log);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("expected an array of 4 numbers"), std::string::npos) << o.output;
  o = run_locbench("match --map " + room_map() + " --log " + log);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("laser scans"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace locbench
