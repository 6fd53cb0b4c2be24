#include "datasets/io/mrclam_reader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::ScratchDir;
using testing::throws_input_error;
using testing::write_bytes;

const std::string kHeader = "# UTIAS Multi-Robot Cooperative Localization and Mapping Dataset\r\n# format\r\n";

// A tiny dataset: robot 2 drives at 1 m/s turning at 0.5 rad/s for 2 s.
void write_dataset(const std::filesystem::path& dir, bool gz, bool barcodes) {
  auto put = [&](const std::string& name, const std::string& text) {
    if (gz) {
      write_bytes(dir / (name + ".gz"), testing::gzip(text));
    } else {
      write_bytes(dir / name, text);
    }
  };
  put("Robot2_Odometry.dat", kHeader + "10.0 \t 1.0 \t 0.5 \r\n11.0\t1.0\t0.5\r\n12.0 0 0\r\n");
  put("Robot2_Groundtruth.dat", kHeader + "9.0 \t 1.0 \t 2.0 \t 0.1 \r\n11.0 \t 2.0 \t 2.0 \t 0.3 \r\n");
  // 102 measurements, one of unknown barcode 43: under the 1% of camera misreads dropped.
  std::string more;
  for (int i = 0; i < 99; ++i) more += "11.7 \t   5 \t 2.0 \t 0.2 \r\n";
  put("Robot2_Measurement.dat", kHeader +
                                    "10.5 \t  14 \t 3.787 \t -0.257 \r\n"
                                    "11.5 \t  43 \t 1.0 \t 0.1 \r\n"
                                    "11.6 \t   5 \t 2.0 \t 0.2 \r\n" +
                                    more);
  if (barcodes) put("Barcodes.dat", kHeader + "  1 \t   5 \r\n  2 \t  14 \r\n");
}

TEST(MrclamReader, ReadsOdometryGroundTruthAndMeasurementsWithSubjectsFromBarcodes) {
  ScratchDir dir;
  const auto folder = dir.path() / "MRCLAM_Dataset6";
  std::filesystem::create_directories(folder);
  write_dataset(folder, true, true);
  const Log log = read_mrclam_robot(folder, 2);
  EXPECT_EQ(log.name, "mrclam6/robot2");
  EXPECT_EQ(log.source, folder.string() + "#robot2");
  ASSERT_EQ(log.odometry.size(), 3u);
  EXPECT_EQ(log.odometry[0].t, 10.0);
  EXPECT_EQ(log.odometry[0].tv, 1.0);
  EXPECT_EQ(log.odometry[0].rv, 0.5);
  ASSERT_EQ(log.truth.size(), 2u);
  EXPECT_EQ(log.truth[1].pose.x, 2.0);
  EXPECT_EQ(log.truth[1].pose.theta, 0.3);
  // Barcode 14 → subject 2, barcode 5 → subject 1; barcode 43 is unknown and dropped.
  ASSERT_EQ(log.landmarks.size(), 101u);
  EXPECT_EQ(log.landmarks[0].subject, 2);
  EXPECT_EQ(log.landmarks[0].range, 3.787);
  EXPECT_EQ(log.landmarks[0].bearing, -0.257);
  EXPECT_EQ(log.landmarks[1].subject, 1);
  EXPECT_EQ(log.params.at("mrclam_measurement_ids"), "subject");
  EXPECT_EQ(log.params.at("mrclam_unknown_barcode_measurements"), "1");
  EXPECT_EQ(log.params.at("mrclam_robot"), "2");
  EXPECT_EQ(log.params.at("mrclam_robot_subjects"), "2");  // the folder holds Robot2_Odometry.dat only
  EXPECT_TRUE(log.landmark_map.empty());                   // no Landmark_Groundtruth.dat
}

TEST(MrclamReader, IntegratesVelocitiesWithTheMidpointRuleFromTheGroundTruthPose) {
  ScratchDir dir;
  write_dataset(dir.path(), false, false);
  const Log log = read_mrclam_robot(dir.path(), 2);
  // Start: ground truth interpolated at t = 10 (halfway between 9 and 11).
  const Pose2 p0 = log.odometry[0].pose;
  EXPECT_DOUBLE_EQ(p0.x, 1.5);
  EXPECT_DOUBLE_EQ(p0.y, 2.0);
  EXPECT_DOUBLE_EQ(p0.theta, 0.2);
  // One second at v = 1, ω = 0.5: heading at the midpoint is 0.2 + 0.25.
  const Pose2 p1 = log.odometry[1].pose;
  EXPECT_DOUBLE_EQ(p1.x, 1.5 + std::cos(0.45));
  EXPECT_DOUBLE_EQ(p1.y, 2.0 + std::sin(0.45));
  EXPECT_DOUBLE_EQ(p1.theta, 0.7);
  EXPECT_DOUBLE_EQ(log.odometry[2].pose.theta, 1.2);
  // Without Barcodes.dat the raw barcodes are kept.
  EXPECT_EQ(log.params.at("mrclam_measurement_ids"), "barcode");
  ASSERT_EQ(log.landmarks.size(), 102u);
  EXPECT_EQ(log.landmarks[1].subject, 43);
}

TEST(MrclamReader, RejectsMissingFilesMalformedLinesAndBackwardsTime) {
  ScratchDir dir;
  write_dataset(dir.path(), false, true);
  EXPECT_TRUE(
      throws_input_error([&] { read_mrclam_robot(dir.path(), 3); }, "Robot3_Odometry.dat", 0, {"missing MRCLAM file"}));
  write_bytes(dir.file("Robot2_Odometry.dat"), kHeader + "10.0 1.0\r\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 2); }, "Robot2_Odometry.dat", 3,
                                 {"expected 3 fields, found 2"}));
  write_bytes(dir.file("Robot2_Odometry.dat"), kHeader + "10.0 1.0 0\r\n9.0 1 0\r\n");
  EXPECT_TRUE(
      throws_input_error([&] { read_mrclam_robot(dir.path(), 2); }, "Robot2_Odometry.dat", 4, {"time goes back"}));
  write_bytes(dir.file("Robot2_Odometry.dat"), kHeader + "10.0 1.0 0\r\n");
  write_bytes(dir.file("Robot2_Measurement.dat"), kHeader + "10.0 x 1 0\r\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 2); }, "Robot2_Measurement.dat", 3,
                                 {"barcode: expected an integer"}));
}

// Real data: UTIAS MRCLAM dataset 6, robot 1.
TEST(MrclamReader, LoadsDataset6Robot1WithPlausibleTimeSpans) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  const Log log = read_mrclam_robot(catalog::data_root() / "mrclam/MRCLAM_Dataset6", 1);
  EXPECT_EQ(log.name, "mrclam6/robot1");
  EXPECT_EQ(log.odometry.size(), 61785u);
  EXPECT_EQ(log.truth.size(), 49241u);
  EXPECT_EQ(log.landmarks.size(), 1941u);  // 1942 measurements, one of unknown barcode 43
  EXPECT_EQ(log.params.at("mrclam_unknown_barcode_measurements"), "1");
  const double odom_span = log.odometry.back().t - log.odometry.front().t;
  EXPECT_NEAR(odom_span, 888.0, 5.0);  // README: ~890 s
  // README: robot 1's ground truth ends about 128 s before its odometry.
  EXPECT_NEAR(log.odometry.back().t - log.truth.back().t, 128.0, 2.0);
  // Odometry starts on the ground truth, and dead reckoning stays near it for a while.
  const Pose2& start = log.odometry.front().pose;
  std::size_t i = 0;
  while (log.truth[i].t < log.odometry.front().t) ++i;
  EXPECT_LT(translation_distance(start, log.truth[i].pose), 0.05);
  std::size_t robots_seen = 0;  // subjects 1–5 are the robots, 6–20 the landmarks
  for (const auto& m : log.landmarks) {
    EXPECT_GE(m.subject, 1);
    EXPECT_LE(m.subject, 20);
    if (m.subject <= 5) ++robots_seen;
  }
  EXPECT_GT(robots_seen, 0u);
}

}  // namespace
}  // namespace locbench::io
