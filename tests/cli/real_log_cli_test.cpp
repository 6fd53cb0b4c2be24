// `locbench run <real-data experiment> --log L --relations R`: any user's log, written here by
// the test itself, through the same harness as the catalog's; bad files keep exit code 2.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "reports/report_json.h"
#include "tests/benchmarks/small_real_log.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::Outcome;
using testing::run_locbench;
using testing::ScratchDir;

const reports::MetricResult* find(const reports::Report& r, const std::string& name) {
  for (const auto& m : r.body.results) {
    if (m.name() == name) return &m;
  }
  return nullptr;
}

TEST(RealLogCli, OdometryAndLaserRealLogsRunOnAUsersLogAndRelations) {
  ScratchDir dir;
  const auto files = testing::write_small_real_log(dir.path());
  const std::string args = " --log " + files.log.string() + " --relations " + files.relations.string() + " -o " +
                           (dir.path() / "out").string();
  Outcome o = run_locbench("run odometry/real_logs" + args);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto odo = reports::read_report(dir.path() / "out/odometry/real_logs.json");
  const auto* m = find(odo, "odometry_raw/small/rpe_rotation");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->summary.n, files.relation_count);

  o = run_locbench("run laser/real_logs" + args + " --set 'matchers=[\"eap\"]' --set 'correctors=[\"pl_icp\"]'");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto laser = reports::read_report(dir.path() / "out/laser/real_logs.json");
  const auto* pl = find(laser, "pl_icp/small/rpe_rotation");
  const auto* raw = find(laser, "odometry_raw/small/rpe_rotation");
  ASSERT_NE(pl, nullptr);
  ASSERT_NE(raw, nullptr);
  EXPECT_LT(pl->summary.mean, 0.2 * raw->summary.mean);
}

TEST(RealLogCli, DiagnosisRealLogsDiagnosesAUsersLogAgainstItsGroundTruth) {
  // A simulated corridor run whose PARAMs are the true model: the checks beside the diagnosis
  // see a path-length ratio of about 1, and the ground truth comes from the TUM file.
  ScratchDir dir;
  const std::string log = (dir.path() / "corridor.clf").string();
  const std::string truth = (dir.path() / "truth.tum").string();
  Outcome o = run_locbench("simulate corridor --seed 7 -o " + log + " --truth-tum " + truth);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  o = run_locbench("run diagnosis/real_logs --log " + log + " --ground-truth " + truth + " -o " +
                   (dir.path() / "out").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.path() / "out/diagnosis/real_logs.json");
  ASSERT_NE(find(r, "diagnose/corridor/causes_detected"), nullptr);
  const auto* ratio = find(r, "check/corridor/path_length_ratio");
  ASSERT_NE(ratio, nullptr);
  EXPECT_NEAR(ratio->summary.mean, 1.0, 0.05);

  o = run_locbench("run diagnosis/real_logs --log " + (dir.path() / "absent.clf").string() + " -o " +
                   (dir.path() / "out2").string());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("absent.clf"), std::string::npos) << o.output;
}

TEST(RealLogCli, SimToRealComparesAUsersLogWithItsTwins) {
  ScratchDir dir;
  const auto scenario = dir.path() / "long.json";
  std::ofstream(scenario) << R"({"preset": "corridor", "world": {"corridor_length": 70.0},
                                 "motion": {"kind": "straight", "distance": 60.0}})";
  const std::string log = (dir.path() / "long.clf").string();
  const std::string truth = (dir.path() / "long.tum").string();
  Outcome o = run_locbench("simulate " + scenario.string() + " --seed 7 -o " + log + " --truth-tum " + truth);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  o = run_locbench("run diagnosis/sim_to_real --log " + log + " --ground-truth " + truth + " -o " +
                   (dir.path() / "out").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.path() / "out/diagnosis/sim_to_real.json");
  const auto* d = find(r, "nominal_twin/long/ks_distance_1s_x");
  ASSERT_NE(d, nullptr);
  EXPECT_GE(d->summary.mean, 0.0);
  EXPECT_LE(d->summary.mean, 1.0);
  EXPECT_NE(find(r, "extended_vs_nominal/long/ks_distance_ratio_mean"), nullptr);

  // A 1 m run (4.5 s) is too short a log to diagnose: exit 2, saying so.
  const auto tiny = dir.path() / "tiny.json";
  std::ofstream(tiny) << R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1.0}})";
  const std::string short_log = (dir.path() / "tiny.clf").string();
  ASSERT_EQ(run_locbench("simulate " + tiny.string() + " --seed 7 -o " + short_log).exit_code, 0);
  o = run_locbench("run diagnosis/sim_to_real --log " + short_log + " -o " + (dir.path() / "out2").string());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("too short a log"), std::string::npos) << o.output;
}

TEST(RealLogCli, AConfigFileNamesTheUsersFiles) {
  ScratchDir dir;
  const auto files = testing::write_small_real_log(dir.path());
  const auto config = dir.path() / "config.json";
  std::ofstream(config) << R"({"odometry/real_logs": {"datasets": [{"name": "mine", "log": ")" << files.log.string()
                        << R"(", "relations": ")" << files.relations.string() << R"("}]}})";
  const Outcome o =
      run_locbench("run odometry/real_logs --config " + config.string() + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.path() / "out/odometry/real_logs.json");
  EXPECT_NE(find(r, "odometry_raw/mine/rpe_translation"), nullptr);
}

TEST(RealLogCli, MissingOrMalformedFilesExitWith2AndNameTheFile) {
  ScratchDir dir;
  const auto files = testing::write_small_real_log(dir.path());
  const std::string out = " -o " + (dir.path() / "out").string();
  Outcome o = run_locbench("run odometry/real_logs --log " + (dir.path() / "absent.clf").string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("absent.clf"), std::string::npos) << o.output;

  o = run_locbench("run odometry/real_logs --log " + files.log.string() + " --relations " +
                   (dir.path() / "absent.relations").string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("absent.relations"), std::string::npos) << o.output;

  std::ofstream(files.relations, std::ios::app) << "1 2 three\n";
  o = run_locbench("run odometry/real_logs --log " + files.log.string() + " --relations " + files.relations.string() +
                   out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("small.relations"), std::string::npos) << o.output;

  o = run_locbench("run odometry/real_logs --relations " + files.relations.string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("--log"), std::string::npos) << o.output;

  o = run_locbench("run odometry/sim_corridor --log " + files.log.string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("does not take real logs"), std::string::npos) << o.output;
}

TEST(RealLogCli, LandmarkFilesWithAnMrclamRobotAreReadAndBadOnesExitWith2NamingTheFile) {
  ScratchDir dir;
  const auto folder = dir.path() / "MRCLAM_Dataset9";
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "Robot1_Odometry.dat") << "# h\n10 0.1 0\n11 0.1 0\n12 0 0\n";
  std::ofstream(folder / "Robot1_Groundtruth.dat") << "# h\n10 0 0 0\n11 0.1 0 0\n12 0.2 0 0\n";
  std::ofstream(folder / "Robot1_Measurement.dat") << "# h\n";
  std::ofstream(dir.file("map.txt")) << "6 1 2\n";
  std::ofstream(dir.file("obs.txt")) << "10.5 6 1.5 0.25\n11 8 2 -0.5\n";  // 8 is not in the map
  const std::string log = " --log " + folder.string() + "#robot1";
  const std::string out = " -o " + (dir.path() / "out").string();
  Outcome o = run_locbench("run odometry/real_logs" + log + " --landmark-map " + dir.file("absent_map.txt").string() +
                           " --landmark-observations " + dir.file("obs.txt").string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("absent_map.txt"), std::string::npos) << o.output;

  o = run_locbench("run odometry/real_logs" + log + " --landmark-map " + dir.file("map.txt").string() +
                   " --landmark-observations " + dir.file("obs.txt").string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("obs.txt:2: id: 8 is not a landmark"), std::string::npos) << o.output;

  o = run_locbench("run odometry/real_logs --landmark-map " + dir.file("map.txt").string() + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("need --log"), std::string::npos) << o.output;
}

TEST(RealLogCli, AnMrclamFolderWithARobotSuffixIsAcceptedAsALog) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  ScratchDir dir;
  const Outcome o =
      run_locbench("run odometry/real_logs --log " + (catalog::data_root() / "mrclam/MRCLAM_Dataset6").string() +
                   "#robot1 -o " + (dir.path() / "out").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto r = reports::read_report(dir.path() / "out/odometry/real_logs.json");
  ASSERT_FALSE(r.body.datasets.empty());
  EXPECT_EQ(r.body.datasets[0].name, "MRCLAM_Dataset6_robot1");
}

}  // namespace
}  // namespace locbench
