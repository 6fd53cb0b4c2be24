// The plain landmark formats: a map "id x y [sigma_x sigma_y]" and observations
// "t id range bearing", and attach_landmarks, which checks them against a log.
#include "datasets/io/landmark_reader.h"

#include <gtest/gtest.h>

#include "datasets/io/landmark_writer.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::ScratchDir;
using testing::throws_input_error;
using testing::write_bytes;

// A log whose odometry starts at t = 10 s.
Log log_from_10s() {
  Log log;
  log.source = "mine.clf";
  for (double t : {10.0, 11.0, 12.0}) log.odometry.push_back({t, Pose2(), 0.0, 0.0});
  return log;
}

TEST(LandmarkMap, ReadsIdsPositionsAndOptionalSigmasSkippingCommentsAndBlankLines) {
  const auto map =
      parse_landmark_map("# id x y sx sy\n\n  6\t0.5 -4.25 0.001 0.002\r\n7 1 2\n  # note\n-3 +1e1 0\n", "map.txt");
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map[0].id, 6);
  EXPECT_EQ(map[0].x, 0.5);
  EXPECT_EQ(map[0].y, -4.25);
  EXPECT_EQ(map[0].sigma_x, 0.001);
  EXPECT_EQ(map[0].sigma_y, 0.002);
  EXPECT_EQ(map[1].id, 7);
  EXPECT_EQ(map[1].sigma_x, 0.0);  // σ absent: 0
  EXPECT_EQ(map[2].id, -3);
  EXPECT_EQ(map[2].x, 10.0);
}

TEST(LandmarkMap, AMalformedLineIsAnInputErrorNamingFileLineAndField) {
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("1 0 0\n2 0\n", "map.txt"); }, "map.txt", 2,
                                 {"expected 3 fields (id x y) or 5 (id x y sigma_x sigma_y), found 2"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("1 0 0 1\n", "map.txt"); }, "map.txt", 1, {"found 4"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("1 0 nan\n", "map.txt"); }, "map.txt", 1, {"y:"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("1 0 0 1 1e999\n", "map.txt"); }, "map.txt", 1, {"sigma_y:"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("# c\n1 0 0 -0.1 1\n", "map.txt"); }, "map.txt", 2,
                                 {"sigma_x: expected a non-negative number [m], found '-0.1'"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("1.5 0 0\n", "map.txt"); }, "map.txt", 1, {"id:"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("4294967296 0 0\n", "map.txt"); }, "map.txt", 1,
                                 {"id: expected an integer in"}));
}

TEST(LandmarkMap, ARepeatedIdIsAnInputErrorNamingBothLines) {
  EXPECT_TRUE(throws_input_error([] { parse_landmark_map("6 0 0\n7 1 1\n6 2 2\n", "map.txt"); }, "map.txt", 3,
                                 {"id: 6 is listed twice (first at line 1)"}));
}

TEST(LandmarkMap, MoreLandmarksThanTheInputLimitAreAnInputErrorNamingTheLimit) {
  std::string text;
  for (int i = 0; i <= 10'000; ++i) text += std::to_string(i) + " 0 0\n";
  EXPECT_TRUE(throws_input_error([&] { parse_landmark_map(text, "big.txt"); }, "big.txt", 0,
                                 {"landmarks: 10001 exceeds the limit 10000"}));
}

TEST(LandmarkObservationsFile, ReadsTimeIdRangeBearingWithTheLineOfEach) {
  const auto obs = parse_landmark_observations("# t id r b\n10.5 6 3.75 -0.25\n\n10.5 7 0 3.5\n11 6 1e1 0\n", "o.txt");
  ASSERT_EQ(obs.readings.size(), 3u);
  EXPECT_EQ(obs.lines, (std::vector<std::size_t>{2, 4, 5}));
  EXPECT_EQ(obs.readings[0].t, 10.5);
  EXPECT_EQ(obs.readings[0].subject, 6);
  EXPECT_EQ(obs.readings[0].range, 3.75);
  EXPECT_EQ(obs.readings[0].bearing, -0.25);
  EXPECT_EQ(obs.readings[1].bearing, 3.5);  // kept as written
  EXPECT_EQ(obs.readings[2].range, 10.0);
}

TEST(LandmarkObservationsFile, MalformedLinesNegativeRangesAndTimesGoingBackAreInputErrors) {
  EXPECT_TRUE(throws_input_error([] { parse_landmark_observations("1 6 1\n", "o.txt"); }, "o.txt", 1,
                                 {"expected 4 fields, found 3"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_observations("1 6 -1 0\n", "o.txt"); }, "o.txt", 1,
                                 {"range: expected a non-negative number [m], found '-1'"}));
  EXPECT_TRUE(
      throws_input_error([] { parse_landmark_observations("1 6 1 inf\n", "o.txt"); }, "o.txt", 1, {"bearing:"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_observations("2 6 1 0\n1 6 1 0\n", "o.txt"); }, "o.txt", 2,
                                 {"time: 1 goes back: line 1 has time 2"}));
  EXPECT_TRUE(throws_input_error([] { parse_landmark_observations("1 x 1 0\n", "o.txt"); }, "o.txt", 1, {"id:"}));
}

// attach_landmarks with the map and the observations read from text, as the files map.txt and o.txt.
void attach_texts(Log& log, const std::string& map, const std::string& observations) {
  attach_landmarks(log, parse_landmark_map(map, "map.txt"), parse_landmark_observations(observations, "o.txt"),
                   "map.txt", "o.txt");
}

TEST(AttachLandmarks, PutsTheMapAndObservationsIntoTheLog) {
  Log log = log_from_10s();
  attach_texts(log, "6 1 2\n7 3 4\n", "10 7 1 0\n12.5 6 2 0.5\n");
  ASSERT_EQ(log.landmark_map.size(), 2u);
  EXPECT_EQ(log.landmark_map[1].x, 3.0);
  ASSERT_EQ(log.landmarks.size(), 2u);
  EXPECT_EQ(log.landmarks[1].subject, 6);
}

TEST(AttachLandmarks, AnObservationOfAnIdMissingFromTheMapIsAnInputErrorAtItsLine) {
  Log log = log_from_10s();
  EXPECT_TRUE(throws_input_error([&] { attach_texts(log, "6 1 2\n", "# h\n10 6 1 0\n11 8 1 0\n"); }, "o.txt", 3,
                                 {"id: 8 is not a landmark of the map map.txt"}));
  EXPECT_TRUE(log.landmarks.empty());  // nothing attached
}

TEST(AttachLandmarks, AnObservationBeforeTheFirstOdometryRecordIsAnInputErrorAtItsLine) {
  Log log = log_from_10s();
  EXPECT_TRUE(throws_input_error([&] { attach_texts(log, "6 1 2\n", "9.5 6 1 0\n"); }, "o.txt", 1,
                                 {"time: 9.5 before the first odometry record at 10"}));
}

TEST(AttachLandmarks, AMapBuiltInCodeWithARepeatedIdIsAnInputError) {
  Log log = log_from_10s();
  EXPECT_TRUE(throws_input_error(
      [&] {
        attach_landmarks(log, {{6, 0, 0, 0, 0}, {6, 1, 1, 0, 0}}, {}, "map", "obs");
      },
      "map", 0, {"id: 6 is listed twice"}));
}

TEST(AttachLandmarkFiles, ReadsPlainAndGzipFilesAndNeedsAMapForObservations) {
  ScratchDir dir;
  write_bytes(dir.file("map.txt.gz"), testing::gzip("6 1 2 0.1 0.1\n"));
  write_bytes(dir.file("obs.txt"), "10 6 1 0\n");
  Log log = log_from_10s();
  attach_landmark_files(log, dir.file("map.txt.gz"), dir.file("obs.txt"));
  EXPECT_EQ(log.landmark_map.size(), 1u);
  EXPECT_EQ(log.landmarks.size(), 1u);

  Log bare = log_from_10s();
  EXPECT_TRUE(throws_input_error([&] { attach_landmark_files(bare, "", dir.file("obs.txt")); }, "obs.txt", 0,
                                 {"need a landmark map"}));
  EXPECT_TRUE(throws_input_error([&] { attach_landmark_files(bare, dir.file("absent.txt"), dir.file("obs.txt")); },
                                 "absent.txt", 0, {}));
}

TEST(AttachLandmarkFiles, ANewMapIsCheckedAgainstTheLogsOwnObservationsExceptRobots) {
  ScratchDir dir;
  write_bytes(dir.file("map.txt"), "6 1 2\n");
  Log log = log_from_10s();
  log.params["mrclam_robot_subjects"] = "1,2";
  log.landmarks = {{10.0, 6, 1.0, 0.0}, {10.5, 2, 1.0, 0.0}};
  attach_landmark_files(log, dir.file("map.txt"), "");
  EXPECT_EQ(log.landmarks.size(), 2u);  // the robot's observation is kept
  log.landmarks.push_back({11.0, 9, 1.0, 0.0});
  EXPECT_TRUE(throws_input_error([&] { attach_landmark_files(log, dir.file("map.txt"), ""); }, "mine.clf", 0,
                                 {"id: 9 (observed at t = 11 s) is not a landmark of the map"}));
}

TEST(LandmarkFiles, WrittenFilesReadBackToTheSameMapAndObservations) {
  ScratchDir dir;
  const std::vector<MapLandmark> map = {{6, 0.58831396, -4.28264845, 0.0000457, 0.00027395}, {-2, 1e20, 0.1, 0, 0}};
  const std::vector<LandmarkReading> obs = {{1248444189.599, 6, 3.787, -0.257}, {1248444189.599, -2, 0, 0.1}};
  for (const char* name : {"m.txt", "m.txt.gz"}) {
    write_landmark_map(map, dir.file(name));
    const auto back = read_landmark_map(dir.file(name));
    ASSERT_EQ(back.size(), map.size());
    for (std::size_t i = 0; i < map.size(); ++i) {
      EXPECT_EQ(back[i].id, map[i].id);
      EXPECT_EQ(back[i].x, map[i].x);
      EXPECT_EQ(back[i].y, map[i].y);
      EXPECT_EQ(back[i].sigma_x, map[i].sigma_x);
      EXPECT_EQ(back[i].sigma_y, map[i].sigma_y);
    }
  }
  write_landmark_observations(obs, dir.file("o.txt.gz"));
  const auto back = read_landmark_observations(dir.file("o.txt.gz"));
  ASSERT_EQ(back.readings.size(), obs.size());
  EXPECT_EQ(back.readings[0].t, obs[0].t);
  EXPECT_EQ(back.readings[1].subject, -2);
  EXPECT_EQ(back.lines, (std::vector<std::size_t>{2, 3}));  // after the header line
  EXPECT_THROW(format_landmark_map({{1, 0, 0, -1, 0}}), std::invalid_argument);
  EXPECT_THROW(format_landmark_observations({{2, 1, 1, 0}, {1, 1, 1, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace locbench::io
