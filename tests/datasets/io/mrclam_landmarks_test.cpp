// MRCLAM landmarks: Landmark_Groundtruth.dat becomes Log::landmark_map, the robots are named in
// mrclam_robot_subjects, and measurements that cannot be placed are InputErrors naming the line.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "datasets/io/mrclam_reader.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::ScratchDir;
using testing::throws_input_error;
using testing::write_bytes;

// Robots 1 and 2 (odometry from t = 10 s), landmarks 6 and 7 (barcodes 63 and 81), and robot 1's
// measurements: `measurements` after a header line.
void write_folder(const std::filesystem::path& dir, const std::string& measurements,
                  const std::string& landmarks =
                      "# Subject # x y sx sy\n  6 \t 0.5 \t -4.25 \t 0.0001 \t 0.0002 \n"
                      "  7 \t 0.75 \t -4.5 \t 0.0001 \t 0.0002 \n") {
  for (int robot : {1, 2}) {
    const std::string stem = fmt::format("Robot{}_", robot);
    write_bytes(dir / (stem + "Odometry.dat"), "# h\n10 0.1 0\n20 0.1 0\n");
    write_bytes(dir / (stem + "Groundtruth.dat"), "# h\n10 0 0 0\n");
  }
  write_bytes(dir / "Barcodes.dat.gz", testing::gzip("# h\n1 5\n2 14\n6 63\n7 81\n"));
  write_bytes(dir / "Robot1_Measurement.dat", "# h\n" + measurements);
  if (!landmarks.empty()) write_bytes(dir / "Landmark_Groundtruth.dat", landmarks);
}

TEST(MrclamLandmarks, TheLandmarkGroundTruthBecomesTheMapAndTheRobotsAreNamed) {
  ScratchDir dir;
  write_folder(dir.path(), "10 63 1 0\n11 14 2 0.5\n12 81 3 -0.5\n");
  const Log log = read_mrclam_robot(dir.path(), 1);
  ASSERT_EQ(log.landmark_map.size(), 2u);
  EXPECT_EQ(log.landmark_map[0].id, 6);
  EXPECT_EQ(log.landmark_map[0].x, 0.5);
  EXPECT_EQ(log.landmark_map[0].y, -4.25);
  EXPECT_EQ(log.landmark_map[0].sigma_x, 0.0001);
  EXPECT_EQ(log.landmark_map[1].sigma_y, 0.0002);
  EXPECT_EQ(log.params.at("mrclam_robot_subjects"), "1,2");
  EXPECT_EQ(mrclam_robot_subjects(log), (std::set<int>{1, 2}));
  // The observation of robot 2 stays, for an experiment to leave out and count.
  ASSERT_EQ(log.landmarks.size(), 3u);
  EXPECT_EQ(log.landmarks[1].subject, 2);
}

TEST(MrclamLandmarks, WithoutTheLandmarkFileTheMapIsEmpty) {
  ScratchDir dir;
  write_folder(dir.path(), "10 63 1 0\n", "");
  EXPECT_TRUE(read_mrclam_robot(dir.path(), 1).landmark_map.empty());
}

TEST(MrclamLandmarks, AMalformedLandmarkLineIsAnInputErrorNamingFileLineAndField) {
  ScratchDir dir;
  write_folder(dir.path(), "10 63 1 0\n", "# h\n6 0.5 -4.25 0.1 0.1\n7 0.75 x 0.1 0.1\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Landmark_Groundtruth.dat", 3, {"y:"}));
  write_folder(dir.path(), "10 63 1 0\n", "# h\n6 0.5 -4.25 0.1 0.1\n7 0.75 1 0.1 1e400\n");
  EXPECT_TRUE(
      throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Landmark_Groundtruth.dat", 3, {"sigma_y:"}));
  write_folder(dir.path(), "10 63 1 0\n", "# h\n6 0.5 -4.25 -0.1 0.1\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Landmark_Groundtruth.dat", 2,
                                 {"sigma_x: expected a non-negative number"}));
  write_folder(dir.path(), "10 63 1 0\n", "# h\n6 0.5 -4.25 0.1 0.1\n6 0.5 -4.25 0.1 0.1\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Landmark_Groundtruth.dat", 3,
                                 {"subject: 6 is listed twice (first at line 2)"}));
  write_folder(dir.path(), "10 63 1 0\n", "# h\n6 0.5\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Landmark_Groundtruth.dat", 2,
                                 {"expected 3 fields"}));
}

TEST(MrclamLandmarks, ASubjectThatIsNeitherALandmarkNorARobotIsAnInputErrorAtItsLine) {
  ScratchDir dir;
  write_folder(dir.path(), "10 63 1 0\n11 14 2 0.5\n");
  std::filesystem::remove(dir.file("Robot2_Odometry.dat"));  // subject 2 is no longer a robot here
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Robot1_Measurement.dat", 3,
                                 {"subject: 2 (barcode 14) is neither a landmark of Landmark_Groundtruth.dat nor a "
                                  "robot (robots: 1)"}));
}

TEST(MrclamLandmarks, AMapWithoutBarcodesIsAnInputError) {
  ScratchDir dir;
  write_folder(dir.path(), "10 63 1 0\n");
  std::filesystem::remove(dir.file("Barcodes.dat.gz"));
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Barcodes.dat", 0, {"missing"}));
}

TEST(MrclamLandmarks, AMeasurementBeforeTheFirstOdometryRecordIsAnInputErrorAtItsLine) {
  ScratchDir dir;
  write_folder(dir.path(), "9.5 63 1 0\n");
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Robot1_Measurement.dat", 2,
                                 {"time: 9.5 before the first odometry record at 10"}));
}

TEST(MrclamLandmarks, UnknownBarcodesAreDroppedAndCountedUpToOnePercent) {
  ScratchDir dir;
  std::string rows;
  for (int i = 0; i < 99; ++i) rows += "12 63 1 0\n";
  write_folder(dir.path(), "11 43 1 0\n" + rows);  // 1 of 100
  const Log log = read_mrclam_robot(dir.path(), 1);
  EXPECT_EQ(log.landmarks.size(), 99u);
  EXPECT_EQ(log.params.at("mrclam_unknown_barcode_measurements"), "1");
}

TEST(MrclamLandmarks, UnknownBarcodesInMoreThanOnePercentAreAnInputErrorAtTheFirst) {
  ScratchDir dir;
  std::string rows;
  for (int i = 0; i < 98; ++i) rows += "12 63 1 0\n";
  write_folder(dir.path(), "10 63 1 0\n11 43 1 0\n" + rows + "13 44 1 0\n");  // 2 of 101
  EXPECT_TRUE(throws_input_error([&] { read_mrclam_robot(dir.path(), 1); }, "Robot1_Measurement.dat", 3,
                                 {"barcode: 43 is not in Barcodes.dat", "2 of 101 measurements", "more than the 1%"}));
}

// Real data: UTIAS MRCLAM dataset 6.
TEST(MrclamLandmarks, Dataset6Robot1HasFifteenMapLandmarks) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  const Log log = read_mrclam_robot(catalog::data_root() / "mrclam/MRCLAM_Dataset6", 1);
  ASSERT_EQ(log.landmark_map.size(), 15u);
  EXPECT_EQ(log.landmark_map.front().id, 6);
  EXPECT_EQ(log.landmark_map.front().x, 0.58831396);
  EXPECT_EQ(log.landmark_map.back().id, 20);
  EXPECT_EQ(log.landmark_map.back().sigma_y, 0.00018146);
  EXPECT_EQ(log.params.at("mrclam_robot_subjects"), "1,2,3,4,5");
}

TEST(MrclamLandmarks, Dataset6RobotsOneToFiveLoadWithTheirFewCameraMisreads) {
  LOCBENCH_REQUIRE_DATA("mrclam/MRCLAM_Dataset6");
  const std::size_t measurements[] = {1942, 4031, 5627, 2399, 5378};
  const std::size_t misreads[] = {1, 0, 2, 3, 0};  // barcodes 43; –; 34 twice; 50 three times
  for (int robot = 1; robot <= 5; ++robot) {
    SCOPED_TRACE(robot);
    const Log log = read_mrclam_robot(catalog::data_root() / "mrclam/MRCLAM_Dataset6", robot);
    EXPECT_EQ(log.landmark_map.size(), 15u);
    EXPECT_EQ(log.params.at("mrclam_unknown_barcode_measurements"), std::to_string(misreads[robot - 1]));
    EXPECT_EQ(log.landmarks.size(), measurements[robot - 1] - misreads[robot - 1]);
    std::size_t robots = 0;
    for (const auto& m : log.landmarks) robots += m.subject <= 5 ? 1 : 0;
    EXPECT_GT(robots, 0u);
  }
}

}  // namespace
}  // namespace locbench::io
