// The real logs under LOCBENCH_DATA (skipped when absent): record counts as published.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>

#include "core/units.h"
#include "datasets/io/carmen_reader.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/log_loader.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/io/relations_reader.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

Log timed_load(const std::string& relative) {
  const auto start = std::chrono::steady_clock::now();
  Log log = load_log((catalog::data_root() / relative).string());
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  ::testing::Test::RecordProperty("load_seconds", std::to_string(took.count()));
  fmt::print("{}: {} records loaded in {:.3f} s\n", relative, log.record_count(), took.count());
  return log;
}

bool all_zero(const Pose2& p) { return p.x == 0.0 && p.y == 0.0 && p.theta == 0.0; }

TEST(RealData, AcesFromBagHas7374FlaserAnd7375OdomWithZeroFlaserPoses) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  const Log log = timed_load("slam_benchmark/clf/aces.from_bag.clf.gz");
  EXPECT_EQ(log.name, "aces.from_bag");
  EXPECT_EQ(log.laser.size(), 7374u);
  EXPECT_EQ(log.odometry.size(), 7375u);
  EXPECT_TRUE(skipped_record_counts(log).empty());
  EXPECT_EQ(log.laser[0].scan.ranges.size(), 180u);
  EXPECT_NEAR(log.laser[0].scan.bearings.back(), deg(89.0), 1e-12);
  EXPECT_TRUE(all_zero(log.laser[100].pose));
  EXPECT_TRUE(all_zero(log.laser[100].odom_pose));
  // The odometry pose of every scan comes from the ODOM records around it.
  std::size_t covered = 0;
  for (const auto& r : log.laser) covered += interpolate_odometry(log, r.scan.timestamp).has_value();
  EXPECT_GE(covered, log.laser.size() - 2);
  const auto [t0, t1] = log.time_span();
  EXPECT_NEAR(t0, 70.179699, 1e-9);
  EXPECT_NEAR(t1, 1435.9, 1e-9);
}

TEST(RealData, IntelFromBagHas13631FlaserAnd26915Odom) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/intel.from_bag.clf.gz");
  const Log log = timed_load("slam_benchmark/clf/intel.from_bag.clf.gz");
  EXPECT_EQ(log.laser.size(), 13631u);
  EXPECT_EQ(log.odometry.size(), 26915u);
  EXPECT_EQ(log.laser.back().scan.ranges.size(), 180u);
}

TEST(RealData, MitCsailHas1988FlaserOf361BeamsAndNoOdom) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/mit-csail.clf.gz");
  const Log log = timed_load("slam_benchmark/clf/mit-csail.clf.gz");
  EXPECT_EQ(log.laser.size(), 1988u);
  EXPECT_TRUE(log.odometry.empty());
  for (const auto& r : log.laser) ASSERT_EQ(r.scan.ranges.size(), 361u);
  const Scan& s = log.laser[0].scan;
  EXPECT_NEAR(s.bearings[1] - s.bearings[0], deg(0.5), 1e-12);
  EXPECT_FALSE(s.valid(24));  // 81.91 m: no return under the 81.9 m SICK convention
  EXPECT_TRUE(s.valid(0));
  // Odometry only in the FLASER odom fields: interpolation falls back to them.
  EXPECT_TRUE(interpolate_odometry(log, log.laser[10].scan.timestamp).has_value());
  EXPECT_EQ(interpolate_odometry(log, log.laser[10].scan.timestamp)->x, log.laser[10].odom_pose.x);
}

struct RelationsCase {
  const char* name;
  const char* relations;
  const char* log;
  std::size_t count;
  double tolerance;  // [s] between relation and scan timestamps
};
void PrintTo(const RelationsCase& c, std::ostream* os) { *os << c.name; }

class RealRelations : public ::testing::TestWithParam<RelationsCase> {};

// Counts from zcat | wc -l; every relation timestamp is a scan timestamp (mit-csail's are
// rounded to 10 µs in the relations file).
TEST_P(RealRelations, LoadWithTheirLineCountAndMatchScanTimestamps) {
  const auto& c = GetParam();
  LOCBENCH_REQUIRE_DATA(c.relations);
  LOCBENCH_REQUIRE_DATA(c.log);
  Log log = timed_load(c.log);
  attach_relations(log, catalog::data_root() / c.relations);
  EXPECT_EQ(log.relations.size(), c.count);
  std::vector<double> scans;
  for (const auto& r : log.laser) scans.push_back(r.scan.timestamp);
  auto distance = [&](double t) {
    const auto it = std::lower_bound(scans.begin(), scans.end(), t);
    double d = std::numeric_limits<double>::infinity();
    if (it != scans.end()) d = *it - t;
    if (it != scans.begin()) d = std::min(d, t - *(it - 1));
    return d;
  };
  double worst = 0.0;
  for (const auto& r : log.relations) worst = std::max({worst, distance(r.t1), distance(r.t2)});
  EXPECT_LE(worst, c.tolerance);
}

INSTANTIATE_TEST_SUITE_P(Freiburg, RealRelations,
                         ::testing::Values(RelationsCase{"aces", "slam_benchmark/relations/aces.relations.gz",
                                                         "slam_benchmark/clf/aces.from_bag.clf.gz", 1279, 0.0},
                                           RelationsCase{"intel", "slam_benchmark/relations/intel.relations.gz",
                                                         "slam_benchmark/clf/intel.from_bag.clf.gz", 2984, 0.0},
                                           RelationsCase{"mit_csail", "slam_benchmark/relations/mit-csail.relations.gz",
                                                         "slam_benchmark/clf/mit-csail.clf.gz", 1172, 1e-5}),
                         [](const ::testing::TestParamInfo<RelationsCase>& p) { return std::string(p.param.name); });

TEST(RealData, AcesSurvivesAWriteReadRoundTrip) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark/clf/aces.from_bag.clf.gz");
  const Log log = read_carmen_log(catalog::data_root() / "slam_benchmark/clf/aces.from_bag.clf.gz");
  testing::ScratchDir dir;
  write_carmen_log(log, dir.file("aces.clf.gz"));
  EXPECT_EQ(testing::log_difference(log, read_carmen_log(dir.file("aces.clf.gz"))), "");
}

TEST(RealData, Mrclam6LoadsThroughTheLoaderWithARobotSuffix) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  const Log log = timed_load("mrclam/MRCLAM_Dataset6#robot4");
  EXPECT_EQ(log.name, "mrclam6/robot4");
  EXPECT_EQ(log.odometry.size(), 52916u);
  EXPECT_EQ(log.truth.size(), 61714u);
  EXPECT_FALSE(log.landmarks.empty());
}

}  // namespace
}  // namespace locbench::io
