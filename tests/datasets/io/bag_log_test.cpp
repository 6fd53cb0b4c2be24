// ROS bags as logs: a simulated log written as a ROS 1 or ROS 2 bag (sqlite3 or MCAP) and read back is the same
// log; topics are chosen by name; a bag that is not what it should be is an InputError naming
// the file, the topic and the message.
#include "datasets/io/bag_log.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <tuple>
#include <typeinfo>

#include "core/angle.h"
#include "core/dead_reckoning.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/io/log_loader.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::ScratchDir;
using testing::throws_input_error;

// A corridor run with ODOM, TRUEPOS and FLASER records and a laser mounted off the axle; the
// ENCODER, COMPASS and PARAM records have no bag topic and are dropped.
Log simulated_log() {
  sim::Scenario s = sim::scenario_from_json(nlohmann::json::parse(R"({"preset": "corridor",
      "odometry": {"enabled": true}, "laser": {"enabled": true, "mount": [0.12, -0.03, 0.05]}})"));
  Log log = sim::simulate(s, 7).log;
  log.encoders.clear();
  log.compass.clear();
  log.params.clear();
  return log;
}

// The same corridor run with its ENCODER, COMPASS and PARAM records (no laser).
Log simulated_log_with_encoders_and_compass() {
  const sim::Scenario s = sim::scenario_from_json(nlohmann::json::parse(R"({"preset": "corridor",
      "odometry": {"enabled": true}})"));
  return sim::simulate(s, 7).log;
}

// The bag's log equals the original: times, positions and velocities exactly, headings to one
// unit in the last place (a quaternion (sin θ/2, cos θ/2) can stand for two neighbouring doubles;
// a heading with ≤ 15 digits, as in a text log, comes back exactly: the Aces test), ranges and
// angles to float precision (LaserScan stores float32).
void expect_same_log(const Log& bag, const Log& original) {
  ASSERT_EQ(bag.odometry.size(), original.odometry.size());
  for (std::size_t i = 0; i < bag.odometry.size(); ++i) {
    const OdometryReading &a = bag.odometry[i], &b = original.odometry[i];
    EXPECT_EQ(a.t, b.t) << i;
    EXPECT_EQ(a.pose.x, b.pose.x) << i;
    EXPECT_EQ(a.pose.y, b.pose.y) << i;
    EXPECT_NEAR(a.pose.theta, b.pose.theta, 1e-15) << i;
    EXPECT_EQ(a.tv, b.tv) << i;
    EXPECT_EQ(a.rv, b.rv) << i;
  }
  ASSERT_EQ(bag.truth.size(), original.truth.size());
  for (std::size_t i = 0; i < bag.truth.size(); ++i) {
    EXPECT_EQ(bag.truth[i].t, original.truth[i].t) << i;
    EXPECT_EQ(bag.truth[i].pose.x, original.truth[i].pose.x) << i;
    EXPECT_EQ(bag.truth[i].pose.y, original.truth[i].pose.y) << i;
    EXPECT_NEAR(bag.truth[i].pose.theta, original.truth[i].pose.theta, 1e-15) << i;
  }
  ASSERT_EQ(bag.laser.size(), original.laser.size());
  for (std::size_t i = 0; i < bag.laser.size(); ++i) {
    const Scan &a = bag.laser[i].scan, &b = original.laser[i].scan;
    EXPECT_EQ(a.timestamp, b.timestamp) << i;
    ASSERT_EQ(a.ranges.size(), b.ranges.size()) << i;
    EXPECT_NEAR(a.max_range, b.max_range, 1e-6);
    for (std::size_t k = 0; k < a.ranges.size(); ++k) {
      EXPECT_NEAR(a.ranges[k], b.ranges[k], 1e-6 * b.ranges[k]) << i << "/" << k;
      EXPECT_EQ(a.valid(k), b.valid(k)) << i << "/" << k;
      EXPECT_NEAR(a.bearings[k], b.bearings[k], 1e-6) << i << "/" << k;
    }
    EXPECT_NEAR(a.sensor_pose.x, 0.12, 1e-12);
    EXPECT_NEAR(a.sensor_pose.y, -0.03, 1e-12);
    EXPECT_NEAR(a.sensor_pose.theta, 0.05, 1e-12);
  }
}

// `log` written as a ROS 1 bag STEM.bag, a ROS 2 bag folder STEM and an MCAP file STEM.mcap in
// `dir`; their names, in that order.
std::vector<std::string> write_every_bag_format(const Log& log, const ScratchDir& dir, const std::string& stem) {
  const std::vector<std::string> names{stem + ".bag", stem, stem + ".mcap"};
  write_bag_log(log, dir.file(names[0]), BagFormat::kRos1);
  write_bag_log(log, dir.file(names[1]), BagFormat::kRos2);
  write_bag_log(log, dir.file(names[2]), BagFormat::kMcap);
  return names;
}

// The messages written as a ROS 1 bag a.bag, a ROS 2 bag folder b and an MCAP file c.mcap in
// `dir`; their names, in that order.
std::vector<std::string> write_every_bag_format(const BagContents& c, const ScratchDir& dir) {
  write_ros1_bag(c, dir.file("a.bag"));
  write_ros2_bag(c, dir.file("b"), "b");
  write_mcap_bag(c, dir.file("c.mcap"));
  return {"a.bag", "b", "c.mcap"};
}

TEST(RosBag, Ros1BagOfASimulatedLogReadsBackAsTheSameLog) {
  ScratchDir dir;
  const Log original = simulated_log();
  ASSERT_GT(original.laser.size(), 10u);
  write_bag_log(original, dir.file("run.bag"), BagFormat::kRos1);
  const Log bag = load_log(dir.file("run.bag").string());
  EXPECT_EQ(bag.name, "run");
  expect_same_log(bag, original);
}

TEST(RosBag, Ros2BagOfASimulatedLogReadsBackAsTheSameLog) {
  ScratchDir dir;
  const Log original = simulated_log();
  write_bag_log(original, dir.file("run2"), BagFormat::kRos2);
  EXPECT_TRUE(std::filesystem::exists(dir.file("run2") / "metadata.yaml"));
  EXPECT_TRUE(std::filesystem::exists(dir.file("run2") / "run2_0.db3"));
  expect_same_log(load_log(dir.file("run2").string()), original);
  // The .db3 file alone is the same bag.
  expect_same_log(load_log((dir.file("run2") / "run2_0.db3").string()), original);
}

TEST(RosBag, McapBagOfASimulatedLogReadsBackAsTheSameLog) {
  ScratchDir dir;
  const Log original = simulated_log();
  write_bag_log(original, dir.file("run.mcap"), BagFormat::kMcap);
  expect_same_log(load_log(dir.file("run.mcap").string()), original);
  // Chunks compressed with zstd (the default), lz4 or not at all; a ROS 2 bag folder of .mcap files.
  for (const std::string compression : {"zstd", "lz4", "none"}) {
    const std::filesystem::path folder = dir.file(compression);
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: mcap\n";
    write_mcap_bag(bag_contents(original), folder / (compression + "_0.mcap"), compression);
    expect_same_log(load_log(folder.string()), original);
  }
  EXPECT_LT(std::filesystem::file_size(dir.file("zstd") / "zstd_0.mcap"),
            std::filesystem::file_size(dir.file("none") / "none_0.mcap"));
}

TEST(RosBag, AMcapBagReadsAsTheSameLogAsTheSqliteBagOfTheSameMessages) {
  ScratchDir dir;
  const Log original = simulated_log();
  write_bag_log(original, dir.file("a.mcap"), BagFormat::kMcap);
  write_bag_log(original, dir.file("a"), BagFormat::kRos2);
  expect_same_log(load_log(dir.file("a.mcap").string()), load_log(dir.file("a").string()));
}

TEST(RosBag, ImuOrientationsReadBackAsTheCompassRecordsTheyWereWrittenFrom) {
  ScratchDir dir;
  const Log original = simulated_log_with_encoders_and_compass();
  ASSERT_GT(original.compass.size(), 100u);
  for (const auto& [bag, format] : std::vector<std::pair<std::string, BagFormat>>{
           {"c.bag", BagFormat::kRos1}, {"c", BagFormat::kRos2}, {"c.mcap", BagFormat::kMcap}}) {
    write_bag_log(original, dir.file(bag), format);
    const Log back = load_log(dir.file(bag).string());
    ASSERT_EQ(back.compass.size(), original.compass.size()) << bag;
    for (std::size_t i = 0; i < back.compass.size(); ++i) {
      EXPECT_EQ(back.compass[i].t, original.compass[i].t) << bag << " " << i;
      EXPECT_NEAR(angle_diff(back.compass[i].heading, original.compass[i].heading), 0.0, 1e-15) << bag << " " << i;
    }
    EXPECT_TRUE(load_log(dir.file(bag).string() + "#heading=none").compass.empty()) << bag;
  }
}

TEST(RosBag, CompressedRos1BagsReadBackAsTheSameLog) {
  ScratchDir dir;
  const Log original = simulated_log();
  for (const std::string compression : {"bz2", "lz4"}) {
    write_ros1_bag(bag_contents(original), dir.file(compression + ".bag"), compression);
    expect_same_log(load_log(dir.file(compression + ".bag").string()), original);
  }
}

TEST(RosBag, ACompressedChunkThatLiesAboutItsSizeIsRefused) {
  ScratchDir dir;
  write_ros1_bag(bag_contents(simulated_log()), dir.file("a.bag"), "bz2");
  std::string bytes = testing::read_bytes(dir.file("a.bag"));
  // The first chunk header's "size=" field (uncompressed bytes) claims 1000 more.
  const auto at = bytes.find("size=");
  ASSERT_NE(at, std::string::npos);
  std::uint32_t size;
  std::memcpy(&size, bytes.data() + at + 5, 4);
  size += 1000;
  std::memcpy(bytes.data() + at + 5, &size, 4);
  testing::write_bytes(dir.file("lie.bag"), bytes);
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("lie.bag").string()); }, "lie.bag", 0,
                                 {"bz2 chunk does not decompress to the", "bytes it claims"}));
}

TEST(RosBag, TopicsAreChosenByNameAfterTheHash) {
  ScratchDir dir;
  const Log original = simulated_log();
  for (const BagFormat f : {BagFormat::kRos1, BagFormat::kRos2, BagFormat::kMcap}) {
    const std::string bag = dir.file(f == BagFormat::kRos1 ? "a.bag" : f == BagFormat::kRos2 ? "a" : "a.mcap").string();
    write_bag_log(original, bag, f);
    // Odometry as the truth (a nav_msgs/Odometry truth topic), no scans, no leading slash needed.
    const Log log = load_log(bag + "#truth=odom,scan=none");
    ASSERT_EQ(log.truth.size(), original.odometry.size());
    EXPECT_EQ(log.truth[5].t, original.odometry[5].t);
    EXPECT_EQ(log.truth[5].pose.x, original.odometry[5].pose.x);
    EXPECT_TRUE(log.laser.empty());
  }
}

TEST(RosBag, ListSaysWhichTopicsAreUsedAndWhereTheLaserSits) {
  ScratchDir dir;
  write_bag_log(simulated_log(), dir.file("run.bag"), BagFormat::kRos1);
  const BagDescription d = describe_bag(*parse_bag_spec(dir.file("run.bag").string() + "#truth=none"));
  ASSERT_EQ(d.topics.size(), 4u);
  std::map<std::string, std::string> roles;
  for (const auto& t : d.topics) roles[t.topic.name] = t.role;
  EXPECT_EQ(roles["/odom"], "odometry (ODOM)");
  EXPECT_EQ(roles["/ground_truth"], "");
  EXPECT_EQ(roles["/scan"], "scan (FLASER)");
  EXPECT_EQ(roles["/tf_static"], "laser mount");
  EXPECT_NEAR(d.topics[1].rate, 10.0, 0.5);  // /odom at 10 Hz
  const std::string notes = ::testing::PrintToString(d.notes);
  EXPECT_NE(notes.find("ground truth: off (#truth=none)"), std::string::npos) << notes;
  EXPECT_NE(notes.find("laser mount laser in base_link from /tf_static: x = 0.12 m"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("header stamps differ"), std::string::npos) << notes;
}

// Contents of a small bag: `n` odometry messages 0.1 s apart, recorded `lag` seconds late.
BagContents odometry_only(int n, double lag) {
  BagContents c;
  for (int i = 0; i < n; ++i) {
    BagPoseMessage m;
    m.time = {0.1 * i + 100.0, 0.1 * i + 100.0 + lag, 0};
    m.child_frame_id = "base_link";
    m.pose = {0.01 * i, 0.0, 0.0};
    c.odom.push_back(m);
  }
  return c;
}

TEST(RosBag, HeaderStampsAreUsedAndALateRecordIsReported) {
  ScratchDir dir;
  write_ros1_bag(odometry_only(20, 0.35), dir.file("late.bag"));
  const Log log = load_log(dir.file("late.bag").string());
  EXPECT_DOUBLE_EQ(log.odometry.front().t, 100.0);
  const BagDescription d = describe_bag(*parse_bag_spec(dir.file("late.bag").string()));
  const std::string notes = ::testing::PrintToString(d.notes);
  EXPECT_NE(notes.find("/odom: header stamps differ from the record times by up to 0.35 s"), std::string::npos)
      << notes;
}

TEST(RosBag, TheLaserMountFollowsAChainOfStaticTransforms) {
  ScratchDir dir;
  BagContents c = odometry_only(5, 0.0);
  BagScanMessage s;
  s.time = {100.1, 100.1, 0};
  s.frame_id = "/laser";  // a ROS 1 frame with a leading slash
  s.angle_min = -1.0;
  s.angle_increment = 0.5;
  s.range_max = 10.0;
  s.ranges = {1.0F, 2.0F, 11.0F, std::numeric_limits<float>::infinity(), 3.0F};
  c.scans.push_back(s);
  c.static_transforms = {{"base_link", "mast", {0.1, 0.0, 0.0}}, {"mast", "laser", {0.0, 0.2, 1.5707963267948966}}};
  write_ros1_bag(c, dir.file("m.bag"));
  const Log log = load_log(dir.file("m.bag").string());
  ASSERT_EQ(log.laser.size(), 1u);
  const Scan& scan = log.laser[0].scan;
  EXPECT_NEAR(scan.sensor_pose.x, 0.1, 1e-12);
  EXPECT_NEAR(scan.sensor_pose.y, 0.2, 1e-12);
  EXPECT_NEAR(scan.sensor_pose.theta, 1.5707963267948966, 1e-12);
  EXPECT_EQ(scan.bearings, (std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}));
  // Beyond range_max and infinity: no return.
  EXPECT_EQ(std::vector<bool>({scan.valid(0), scan.valid(1), scan.valid(2), scan.valid(3), scan.valid(4)}),
            std::vector<bool>({true, true, false, false, true}));
  EXPECT_NEAR(log.laser[0].odom_pose.x, 0.01, 1e-12);  // the odometry at the scan's stamp
  // Frames named after '#' must be joined by the transforms; the defaults may fall back.
  EXPECT_NEAR(load_log(dir.file("m.bag").string() + "#laser=mast").laser[0].scan.sensor_pose.x, 0.1, 1e-12);
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("m.bag").string() + "#base=base_footprint"); }, "m.bag", 0,
                                 {"laser mount: no transform from base_footprint to laser in /tf_static",
                                  "expected the frames named by #base= and #laser="}));
}

TEST(RosBag, TheAcesCatalogLogReadsBackFromItsBagsRecordForRecord) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  ScratchDir dir;
  const Log aces = load_log((catalog::data_root() / "slam_benchmark/clf/aces.from_bag.clf.gz").string());
  ASSERT_GT(aces.odometry.size(), 7000u);
  for (const std::string& bag : write_every_bag_format(aces, dir, "aces")) {
    const Log back = load_log(dir.file(bag).string());
    ASSERT_EQ(back.odometry.size(), aces.odometry.size()) << bag;
    for (std::size_t i = 0; i < aces.odometry.size(); ++i) {
      ASSERT_EQ(back.odometry[i].t, aces.odometry[i].t) << bag << " " << i;  // epoch times, to the last bit
      ASSERT_TRUE(testing::same_pose(back.odometry[i].pose, aces.odometry[i].pose))
          << bag << " " << i << std::setprecision(17) << " " << back.odometry[i].pose.x << " "
          << back.odometry[i].pose.y << " " << back.odometry[i].pose.theta << " vs " << aces.odometry[i].pose.x << " "
          << aces.odometry[i].pose.y << " " << aces.odometry[i].pose.theta;
    }
    ASSERT_EQ(back.laser.size(), aces.laser.size()) << bag;
    for (std::size_t i = 0; i < aces.laser.size(); i += 97) {
      const Scan &a = back.laser[i].scan, &b = aces.laser[i].scan;
      ASSERT_EQ(a.timestamp, b.timestamp) << bag << " " << i;
      ASSERT_EQ(a.ranges.size(), b.ranges.size());
      for (std::size_t k = 0; k < a.ranges.size(); ++k) {
        EXPECT_NEAR(a.ranges[k], b.ranges[k], 1e-6 * b.ranges[k]) << bag << " " << i << "/" << k;
        EXPECT_NEAR(a.bearings[k], b.bearings[k], 1e-6) << bag << " " << i << "/" << k;
      }
    }
  }
}

// ---- hostile bags: exit 2 material, never a crash --------------------------------------------

TEST(RosBag, AMissingTopicNamesTheTopicAndListsTheBagsTopics) {
  ScratchDir dir;
  write_ros1_bag(odometry_only(5, 0.0), dir.file("a.bag"));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("a.bag").string() + "#odom=/wheel_odom"); }, "a.bag", 0,
                                 {"#odom=/wheel_odom: no such topic", "topics: /odom (nav_msgs/Odometry)"}));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("a.bag").string() + "#odom=none"); }, "a.bag", 0,
                                 {"no odometry topic", "#odom=TOPIC"}));
}

TEST(RosBag, AWrongMessageTypeOnTheChosenTopicIsRefused) {
  ScratchDir dir;
  for (const std::string& bag : write_every_bag_format(simulated_log(), dir, "a")) {
    EXPECT_TRUE(throws_input_error([&] { load_log(dir.file(bag).string() + "#odom=/scan"); }, bag, 0,
                                   {"topic /scan (#odom=) is a sensor_msgs/LaserScan, expected nav_msgs/Odometry"}));
  }
}

TEST(RosBag, AMessageThatIsNotItsDeclaredTypeIsRefusedByMessageNumber) {
  ScratchDir dir;
  write_bag_log(simulated_log(), dir.file("b"), BagFormat::kRos2);
  // The scans' topic claims Odometry: the first scan does not decode as one.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir.file("b") / "b_0.db3").string().c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "UPDATE topics SET type='nav_msgs/msg/Odometry' WHERE name='/scan'", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("b").string() + "#odom=/scan,scan=none"); }, "b_0.db3", 0,
                                 {"topic /scan, message 1: not a CDR-serialized nav_msgs/Odometry"}));
}

TEST(RosBag, TruncatedBagsAreInputErrors) {
  ScratchDir dir;
  write_every_bag_format(simulated_log(), dir, "a");
  const auto mcap_size = std::filesystem::file_size(dir.file("a.mcap"));
  for (const auto& [file, keep] :
       std::vector<std::pair<std::filesystem::path, std::uintmax_t>>{{dir.file("a.bag"), 5000},
                                                                     {dir.file("a.bag"), 13},
                                                                     {dir.file("a") / "a_0.db3", 9000},
                                                                     {dir.file("a") / "a_0.db3", 100},
                                                                     {dir.file("a.mcap"), mcap_size / 2},
                                                                     {dir.file("a.mcap"), mcap_size - 1},
                                                                     {dir.file("a.mcap"), 100},
                                                                     {dir.file("a.mcap"), 5}}) {
    const std::filesystem::path copy = dir.file("t") / std::to_string(keep) / file.filename();
    std::filesystem::create_directories(copy.parent_path());
    std::filesystem::copy_file(file, copy);
    std::filesystem::resize_file(copy, keep);
    EXPECT_TRUE(throws_input_error([&] { load_log(copy.string()); }, copy.filename().string(), 0, {""}))
        << copy << " " << keep;
  }
}

// A property of both readers: a bag with random bytes overwritten either reads (the bytes hit a
// value nothing checks, e.g. a pose digit) or is an InputError naming the bag — never another
// exception, a crash or a sanitizer report (the test build runs ASan and UBSan). 300 ROS 1 and
// 100 ROS 2 mutants, 1–8 bytes each, seeded.
TEST(RosBag, RandomlyCorruptedBagsReadOrAreInputErrorsNamingTheBag) {
  ScratchDir dir;
  BagContents c = odometry_only(40, 0.0);
  c.truth = c.odom;
  write_ros1_bag(c, dir.file("a.bag"));
  write_ros2_bag(c, dir.file("b"), "b");
  write_mcap_bag(c, dir.file("c.mcap"), "none");  // uncompressed: the mutations reach the messages too
  const auto read_bytes = [](const std::filesystem::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  Rng rng(26);
  const auto pick = [&](std::size_t n) { return std::min(n - 1, static_cast<std::size_t>(rng.uniform() * n)); };
  int read = 0, refused = 0;
  for (const auto& [file, name, mutants] :
       std::vector<std::tuple<std::filesystem::path, std::string, int>>{{dir.file("a.bag"), "m.bag", 300},
                                                                        {dir.file("b") / "b_0.db3", "m.db3", 100},
                                                                        {dir.file("c.mcap"), "m.mcap", 100}}) {
    const std::string original = read_bytes(file);
    ASSERT_GT(original.size(), 100u);
    for (int k = 0; k < mutants; ++k) {
      std::string bytes = original;
      const std::size_t n = 1 + pick(8);
      for (std::size_t i = 0; i < n; ++i) bytes[pick(bytes.size())] = static_cast<char>(pick(256));
      const std::filesystem::path mutant = dir.file(name);
      std::ofstream(mutant, std::ios::binary | std::ios::trunc) << bytes;
      try {
        load_log(mutant.string());
        ++read;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << file.filename() << " mutant " << k << ": " << typeid(e).name() << ": " << e.what();
      }
    }
  }
  EXPECT_GT(refused, 100) << "the mutations reach the checks (" << read << " read)";
}

TEST(RosBag, StampsOutOfOrderAreRefusedNamingTheMessage) {
  ScratchDir dir;
  BagContents c = odometry_only(6, 0.0);
  std::swap(c.odom[3].time.stamp, c.odom[4].time.stamp);  // recorded in order, stamped out of order
  for (const std::string& bag : write_every_bag_format(c, dir)) {
    EXPECT_TRUE(throws_input_error([&] { load_log(dir.file(bag).string()); }, bag, 0,
                                   {"topic /odom, message 5: header stamp", "expected stamps in time order"}));
  }
}

TEST(RosBag, ABadTopicChoiceIsRefusedWithTheAcceptedKeys) {
  ScratchDir dir;
  write_ros1_bag(odometry_only(3, 0.0), dir.file("a.bag"));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("a.bag").string() + "#odo=/odom"); }, "a.bag#odo=/odom", 0,
                                 {"unknown key \"odo\"",
                                  "keys odom, truth, scan, heading, joints, left, right, ticks_per_rev, radius, "
                                  "left_radius, right_radius, wheelbase, base, laser"}));
  EXPECT_TRUE(
      throws_input_error([&] { load_log(dir.file("a.bag").string() + "#odom="); }, "a.bag#odom=", 0, {"no value"}));
}

TEST(RosBag, FileCompressedRos2BagsAreRefusedByNameAndAFileThatIsNotMcapIsAnInputError) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.file("z"));
  std::ofstream(dir.file("z") / "metadata.yaml") << "rosbag2_bagfile_information:\n  compression_format: zstd\n";
  std::ofstream(dir.file("z") / "z_0.db3.zstd") << "x";
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("z").string()); }, "metadata.yaml", 2,
                                 {"compressed ROS 2 bags are not read"}));
  std::filesystem::create_directories(dir.file("y"));
  std::ofstream(dir.file("y") / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: mcap\n";
  std::ofstream(dir.file("y") / "y_0.mcap.zstd") << "x";
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("y").string()); }, "y_0.mcap.zstd", 0,
                                 {"compressed file by file: not read"}));
  std::filesystem::create_directories(dir.file("m"));
  std::ofstream(dir.file("m") / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: mcap\n";
  std::ofstream(dir.file("m") / "m_0.mcap") << "x";
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("m").string()); }, "m_0.mcap", 0,
                                 {"expected an MCAP file of ROS 2 messages"}));
}

// An MCAP chunk record: opcode 0x06, then its length, message start and end times, and the
// uncompressed size (little-endian uint64s), which this test raises by 1000 and then to 2^60. The
// MCAP library allocates what a chunk claims and asserts an uncompressed chunk's claim: both are
// checked before it reads (found by fuzz_bags).
TEST(RosBag, AnMcapChunkThatLiesAboutItsSizeIsRefused) {
  ScratchDir dir;
  const Log original = simulated_log();
  for (const std::string compression : {"zstd", "lz4", "none"}) {
    for (const bool exabytes : {false, true}) {
      write_mcap_bag(bag_contents(original), dir.file("a.mcap"), compression);
      std::string bytes = testing::read_bytes(dir.file("a.mcap"));
      std::size_t at = 8;  // after the magic
      while (at + 9 <= bytes.size() && bytes[at] != 0x06) {
        std::uint64_t length = 0;
        std::memcpy(&length, bytes.data() + at + 1, 8);
        at += 9 + length;
      }
      ASSERT_LT(at + 33, bytes.size()) << "a chunk record";
      std::uint64_t size = 0;
      std::memcpy(&size, bytes.data() + at + 25, 8);
      size = exabytes ? std::uint64_t{1} << 60 : size + 1000;
      std::memcpy(bytes.data() + at + 25, &size, 8);
      testing::write_bytes(dir.file("lie.mcap"), bytes);
      const char* expected = exabytes                ? "a chunk claims 1152921504606846976 bytes uncompressed"
                             : compression == "none" ? "an uncompressed chunk of"
                                                     : "reading its messages";
      EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("lie.mcap").string()); }, "lie.mcap", 0, {expected}))
          << compression << " " << exabytes;
    }
  }
}

TEST(RosBag, AnImuWithoutAnOrientationIsRefusedAsAHeading) {
  ScratchDir dir;
  BagContents c = odometry_only(5, 0.0);
  for (const BagPoseMessage& o : c.odom) c.headings.push_back({o.time, "imu", 0.3, false});
  for (const std::string& bag : write_every_bag_format(c, dir)) {
    EXPECT_TRUE(throws_input_error([&] { load_log(dir.file(bag).string()); }, bag, 0,
                                   {"topic /imu, message 1: the IMU gives no orientation"}));
    EXPECT_TRUE(load_log(dir.file(bag).string() + "#heading=none").compass.empty());
  }
}

// Velocity commands as the odometry: geometry_msgs/Twist (no header: the record times) and
// TwistStamped (the header stamps); ODOM's tv, rv are the commands and its pose their dead
// reckoning, each command held until the next, as a velocity log's is.
TEST(RosBag, VelocityCommandsReadBackAsOdometryWithTheirDeadReckoning) {
  ScratchDir dir;
  const Log original = simulated_log();
  BagContents c = bag_contents(original);
  for (BagPoseMessage& m : c.odom) m.time.record_time = m.time.stamp + 0.005;  // recorded 5 ms after the stamp
  const Trajectory expected = dead_reckon_velocities(original.odometry, Pose2::identity());
  for (const std::string type : {kTwistType, kTwistStampedType}) {
    c.odom_type = type;
    write_ros1_bag(c, dir.file("t.bag"));
    write_ros2_bag(c, dir.file("t" + std::to_string(type.size())), "t");
    write_mcap_bag(c, dir.file("t.mcap"));
    for (const std::filesystem::path& bag :
         {dir.file("t.bag"), dir.file("t" + std::to_string(type.size())), dir.file("t.mcap")}) {
      const Log back = load_log(bag.string());
      ASSERT_EQ(back.odometry.size(), original.odometry.size()) << type << " " << bag;
      for (std::size_t i = 0; i < back.odometry.size(); ++i) {
        const double t = original.odometry[i].t + (type == kTwistType ? 0.005 : 0.0);
        ASSERT_NEAR(back.odometry[i].t, t, 1e-9) << type << " " << bag << " " << i;
        ASSERT_EQ(back.odometry[i].tv, original.odometry[i].tv);
        ASSERT_EQ(back.odometry[i].rv, original.odometry[i].rv);
        ASSERT_NEAR(back.odometry[i].pose.x, expected.poses()[i].pose.x, 1e-6) << type << " " << bag << " " << i;
        ASSERT_NEAR(back.odometry[i].pose.y, expected.poses()[i].pose.y, 1e-6) << type << " " << bag << " " << i;
        ASSERT_NEAR(back.odometry[i].pose.theta, expected.poses()[i].pose.theta, 1e-9);
      }
    }
  }
}

// Wheel encoders from sensor_msgs/JointState: a simulated run's ENCODER ticks written as wheel
// angles (ticks · 2π/N, N = 4096 per revolution) beside other joints, read back with
// ticks_per_rev=4096 as the same ticks, and with radius= and wheelbase= as the same nominal model.
TEST(RosBag, WheelJointAnglesReadBackAsTheEncoderTicksTheyWereWrittenFrom) {
  ScratchDir dir;
  const Log original = simulated_log_with_encoders_and_compass();
  ASSERT_GT(original.encoders.size(), 100u);
  const NominalModel model = *original.nominal_model();
  constexpr double kTicksPerRev = 4096.0;
  const double left_radius = model.meters_per_tick_left * kTicksPerRev / (2.0 * kPi);
  const double right_radius = model.meters_per_tick_right * kTicksPerRev / (2.0 * kPi);
  BagContents c = bag_contents(original);
  for (const EncoderReading& e : original.encoders) {
    c.joints.push_back({{e.t, e.t, 0},
                        {"caster_joint", "right_wheel_joint", "left_wheel_joint"},
                        {0.5, 2.0 * kPi * static_cast<double>(e.right) / kTicksPerRev,
                         2.0 * kPi * static_cast<double>(e.left) / kTicksPerRev}});
  }
  write_ros1_bag(c, dir.file("j.bag"));
  write_ros2_bag(c, dir.file("j"), "j");
  write_mcap_bag(c, dir.file("j.mcap"));
  const std::string choice =
      fmt::format("#ticks_per_rev=4096,left_radius={:.17g},right_radius={:.17g},wheelbase={:.17g}", left_radius,
                  right_radius, model.wheelbase);
  for (const std::string bag : {"j.bag", "j", "j.mcap"}) {
    const Log back = load_log(dir.file(bag).string() + choice);
    ASSERT_EQ(back.encoders.size(), original.encoders.size()) << bag;
    for (std::size_t i = 0; i < back.encoders.size(); ++i) {
      EXPECT_EQ(back.encoders[i].t, original.encoders[i].t) << bag << " " << i;
      EXPECT_EQ(back.encoders[i].left, original.encoders[i].left) << bag << " " << i;
      EXPECT_EQ(back.encoders[i].right, original.encoders[i].right) << bag << " " << i;
    }
    ASSERT_TRUE(back.nominal_model()) << bag;
    EXPECT_NEAR(back.nominal_model()->meters_per_tick_left, model.meters_per_tick_left, 1e-15) << bag;
    EXPECT_NEAR(back.nominal_model()->meters_per_tick_right, model.meters_per_tick_right, 1e-15) << bag;
    EXPECT_EQ(back.nominal_model()->wheelbase, model.wheelbase) << bag;
    EXPECT_FALSE(load_log(dir.file(bag).string()).nominal_model()) << "no radius, no model";
    EXPECT_TRUE(throws_input_error([&] { load_log(dir.file(bag).string() + "#left=front_wheel_joint"); }, bag, 0,
                                   {"message 1: no position of joint front_wheel_joint"}));
  }
}

}  // namespace
}  // namespace locbench::io
