// One laser scan as JSON (the laser_line_extraction test data): fields, both bearing forms,
// and clear errors for everything else.
#include "datasets/io/scan_json_reader.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

std::filesystem::path write(const testing::ScratchDir& dir, const std::string& text) {
  const auto p = dir.file("scan.json");
  std::ofstream(p) << text;
  return p;
}

TEST(ScanJsonReader, ReadsRangesWithBearingsOrWithAngleMinAndIncrement) {
  testing::ScratchDir dir;
  Scan s = read_scan_json(write(dir, R"({"ranges": [1.0, 2.5], "bearings": [-0.1, 0.1]})"));
  EXPECT_EQ(s.ranges, (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(s.bearings, (std::vector<double>{-0.1, 0.1}));
  s = read_scan_json(write(dir, R"({"ranges": [1, 2, 3], "angle_min": -1.0, "angle_increment": 0.5,
                                     "range_max": 4})"));
  EXPECT_EQ(s.bearings, (std::vector<double>{-1.0, -0.5, 0.0}));
  EXPECT_EQ(s.max_range, 4.0);
}

TEST(ScanJsonReader, MalformedInputNamesTheFileAndWhatWasExpected) {
  testing::ScratchDir dir;
  const auto expect_error = [&](const std::string& text, const std::string& what) {
    try {
      read_scan_json(write(dir, text));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("scan.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error(R"({"bearings": [0.0]})", "\"ranges\"");
  expect_error(R"({"ranges": [1.0, "x"], "bearings": [0, 1]})", "numbers only");
  expect_error(R"({"ranges": [1.0, 2.0], "bearings": [0.0]})", "as many bearings as ranges");
  expect_error(R"({"ranges": [1.0]})", "\"bearings\" or");
  expect_error(R"({"ranges": [1.0], )", "invalid JSON");
  expect_error(R"([1, 2])", "a JSON object");
}

RC_GTEST_PROP(ScanJsonReader, AnyTruncationOfAValidFileIsAnErrorNotACrash, ()) {
  const std::string valid = R"({"ranges": [1.0, 2.0, 3.0], "bearings": [-0.5, 0.0, 0.5]})";
  const auto cut = *rc::gen::inRange<std::size_t>(0, valid.size());
  testing::ScratchDir dir;
  const auto p = write(dir, valid.substr(0, cut));
  RC_ASSERT_THROWS_AS(read_scan_json(p), InputError);
}

TEST(ScanJsonReader, ReadsTheQueensHallwayScans) {
  LOCBENCH_REQUIRE_DATA("laser_scans/kam3k_queens/laser_scan_1.json.gz");
  const Scan s = read_scan_json(catalog::data_root() / "laser_scans/kam3k_queens/laser_scan_1.json.gz");
  EXPECT_EQ(s.ranges.size(), 541u);  // SICK LMS, 270° at 0.5°
  EXPECT_NEAR(s.bearings.back() - s.bearings.front(), 3 * kPi / 2, 1e-5);
}

}  // namespace
}  // namespace locbench::io
