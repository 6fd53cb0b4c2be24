// ROS bags in the verbs: `list` describes a bag's topics, and `diagnose` and the real-data
// experiments give on a bag exactly what they give on the same records as a CARMEN log.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "datasets/io/bag_log.h"
#include "datasets/io/log_loader.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::Outcome;
using testing::run_locbench;
using testing::run_shell;
using testing::ScratchDir;

// A corridor run as a CARMEN log, a ROS 1 bag, a ROS 2 bag and an MCAP file, and same.clf: the CARMEN log
// without what a bag does not hold (ENCODER and PARAM records; COMPASS goes to /imu).
class RosBagCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_.path() / "s.json")
        << R"({"preset": "corridor", "odometry": {"enabled": true}, "laser": {"enabled": true}})";
    const Outcome o = run_locbench("simulate " + path("s.json") + " --seed 7 -o " + path("run.clf") + " --ros1-bag " +
                                   path("run.bag") + " --ros2-bag " + path("run2") + " --mcap " + path("run.mcap"));
    ASSERT_EQ(o.exit_code, 0) << o.output;
    ASSERT_EQ(run_shell("grep -v '^ENCODER\\|^PARAM' " + path("run.clf") + " > " + path("same.clf")).exit_code, 0);
  }
  std::string path(const std::string& name) const { return (dir_.path() / name).string(); }
  // The command's output with the log's path taken out.
  std::string output_of(const std::string& args, const std::string& log) const {
    const Outcome o = run_locbench(args);
    EXPECT_EQ(o.exit_code, 0) << args << "\n" << o.output;
    std::string out = o.output;
    for (auto at = out.find(log); at != std::string::npos; at = out.find(log)) out.replace(at, log.size(), "LOG");
    return out;
  }

  ScratchDir dir_;
};

TEST_F(RosBagCli, ListPrintsEachTopicWithTypeCountRateAndUse) {
  for (const std::string bag : {"run.bag", "run2", "run.mcap"}) {
    const Outcome o = run_locbench("list " + path(bag));
    ASSERT_EQ(o.exit_code, 0) << o.output;
    for (const std::string line :
         {"/odom                        nav_msgs/Odometry                             405      10 Hz  odometry (ODOM)",
          "/ground_truth                geometry_msgs/PoseStamped                     162       4 Hz  truth (TRUEPOS)",
          "/scan                        sensor_msgs/LaserScan                         203       5 Hz  scan (FLASER)",
          "/tf_static                   tf2_msgs/TFMessage                              1       - Hz  laser mount",
          "/imu                         sensor_msgs/Imu                               163   4.005 Hz  heading "
          "(COMPASS)",
          "405 ODOM, 163 COMPASS, 203 FLASER, 162 TRUEPOS"}) {
      EXPECT_NE(o.output.find(line), std::string::npos) << line << " in\n" << o.output;
    }
  }
  const Outcome o = run_locbench("list '" + path("run.bag") + "#truth=none,scan=/ground_truth'");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("topic /ground_truth (#scan=) is a geometry_msgs/PoseStamped, expected "
                          "sensor_msgs/LaserScan for the laser scans"),
            std::string::npos)
      << o.output;
}

TEST_F(RosBagCli, DiagnoseOnABagEqualsDiagnoseOnTheSameRecordsAsCarmen) {
  const std::string carmen = output_of("diagnose " + path("same.clf"), path("same.clf"));
  EXPECT_NE(carmen.find("verdict:"), std::string::npos) << carmen;
  EXPECT_EQ(output_of("diagnose " + path("run.bag"), path("run.bag")), carmen);
  EXPECT_EQ(output_of("diagnose " + path("run2"), path("run2")), carmen);
  EXPECT_EQ(output_of("diagnose " + path("run.mcap"), path("run.mcap")), carmen);
}

TEST_F(RosBagCli, TopicOptionsChooseWhatTheHashSuffixChooses) {
  for (const std::string bag : {"run.bag", "run2", "run.mcap"}) {
    const std::string by_suffix =
        output_of("diagnose '" + path(bag) + "#odom=/odom,truth=/ground_truth,heading=none'", path(bag));
    const std::string by_options =
        output_of("diagnose " + path(bag) + " --odom /odom --truth /ground_truth --heading none", path(bag));
    EXPECT_EQ(by_options.substr(by_options.find('\n')), by_suffix.substr(by_suffix.find('\n'))) << bag;
    EXPECT_EQ(by_suffix.find("compass"), std::string::npos) << "the heading is off: " << by_suffix;
  }
  const Outcome o = run_locbench("diagnose " + path("run.clf") + " --odom /odom");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("run.clf is not a bag"), std::string::npos) << o.output;
}

TEST_F(RosBagCli, ARealDataExperimentOnABagEqualsItOnTheSameRecordsAsCarmen) {
  // The dataset is named after its file (same.clf, same.bag and a folder same are all "same").
  ASSERT_EQ(run_shell("cd " + path("") +
                      " && mkdir b f m && cp run.bag b/same.bag && cp -r run2 f/same && cp run.mcap m/same.mcap")
                .exit_code,
            0);
  const auto run = [&](const std::string& log) {
    return output_of("run diagnosis/real_logs --log " + path(log) + " -o " + path("out"), path(log));
  };
  const std::string carmen = run("same.clf");
  EXPECT_NE(carmen.find("diagnose/same/causes_detected"), std::string::npos) << carmen;
  EXPECT_EQ(run("b/same.bag"), carmen);
  EXPECT_EQ(run("f/same"), carmen);
  EXPECT_EQ(run("m/same.mcap"), carmen);
}

TEST(RosBagCatalogCli, DiagnoseOnTheAcesLogAsABagEqualsDiagnoseOnTheCatalogLog) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  ScratchDir dir;
  const std::string relations = (catalog::data_root() / "slam_benchmark/relations/aces.relations.gz").string();
  const Log aces = io::load_log((catalog::data_root() / "slam_benchmark/clf/aces.from_bag.clf.gz").string());
  io::write_bag_log(aces, dir.path() / "aces.bag", io::BagFormat::kRos1);
  io::write_bag_log(aces, dir.path() / "aces", io::BagFormat::kRos2);
  io::write_bag_log(aces, dir.path() / "aces.mcap", io::BagFormat::kMcap);
  const auto diagnose = [&](const std::string& log) {
    const Outcome o = run_locbench("diagnose " + log + " --relations " + relations);
    EXPECT_EQ(o.exit_code, 0) << o.output;
    return o.output.substr(o.output.find('\n'));  // without the "log:" line
  };
  const std::string carmen = diagnose((catalog::data_root() / "slam_benchmark/clf/aces.from_bag.clf.gz").string());
  EXPECT_NE(carmen.find("verdict: The nominal model misses"), std::string::npos) << carmen;
  EXPECT_EQ(diagnose((dir.path() / "aces.bag").string()), carmen);
  EXPECT_EQ(diagnose((dir.path() / "aces").string()), carmen);
  EXPECT_EQ(diagnose((dir.path() / "aces.mcap").string()), carmen);
}

}  // namespace
}  // namespace locbench
