// Malformed input: every error names the file, the line and what was expected.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "datasets/io/carmen_reader.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/log_loader.h"
#include "datasets/io/relations_reader.h"
#include "io_test_support.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

using testing::gzip;
using testing::ScratchDir;
using testing::throws_input_error;
using testing::write_bytes;

const std::string kGood = "ODOM 0 0 0 0 0 0 1 h 1\n";

auto parse(const std::string& text, const std::string& name = "aces.clf") {
  return [=] { parse_carmen_log(text, name); };
}

TEST(CarmenReader, RejectsOdomWithMissingFieldNamingFileAndLine) {
  EXPECT_TRUE(throws_input_error(parse(kGood + kGood + "ODOM 0 0 0 0 0 1 h\n"), "aces.clf", 3,
                                 {"ODOM", "expected 9 fields after the tag, found 7"}));
}

TEST(CarmenReader, RejectsOdomWithExtraField) {
  EXPECT_TRUE(throws_input_error(parse("ODOM 0 0 0 0 0 0 1 h 1 9\n"), "aces.clf", 1,
                                 {"ODOM", "expected 9 fields", "found 10"}));
}

TEST(CarmenReader, RejectsBadNumberNamingTheFieldAndToken) {
  EXPECT_TRUE(throws_input_error(parse("# c\nODOM 0 0 0.1x 0 0 0 1 h 1\n"), "aces.clf", 2,
                                 {"ODOM", "theta", "expected a finite number", "'0.1x'"}));
}

TEST(CarmenReader, RejectsNanAndInfinity) {
  EXPECT_TRUE(throws_input_error(parse("ODOM nan 0 0 0 0 0 1 h 1\n"), "aces.clf", 1,
                                 {"x: expected a finite number, found 'nan'"}));
  EXPECT_TRUE(throws_input_error(parse("COMPASS -inf 1 h 1\n"), "aces.clf", 1, {"COMPASS", "heading", "'-inf'"}));
  EXPECT_TRUE(
      throws_input_error(parse("TRUEPOS 0 0 0 0 0 0 1e999 h 1\n"), "aces.clf", 1, {"TRUEPOS", "timestamp", "'1e999'"}));
}

TEST(CarmenReader, RejectsFlaserWhoseFieldCountDoesNotMatchItsBeamCount) {
  EXPECT_TRUE(throws_input_error(parse("FLASER 3 1 2 0 0 0 0 0 0 1 h 1\n"), "aces.clf", 1,
                                 {"FLASER", "expected 1 + n + 9 = 13 fields", "n = 3", "found 12"}));
  EXPECT_TRUE(throws_input_error(parse("FLASER 99999999999999 1 2\n"), "aces.clf", 1, {"FLASER", "found 3"}));
}

TEST(CarmenReader, RejectsFlaserWithoutBeams) {
  EXPECT_TRUE(throws_input_error(parse("FLASER 0 0 0 0 0 0 0 1 h 1\n"), "aces.clf", 1,
                                 {"FLASER", "beam count n: expected at least 1, found 0"}));
  EXPECT_TRUE(throws_input_error(parse("FLASER\n"), "aces.clf", 1, {"FLASER", "beam count"}));
  EXPECT_TRUE(throws_input_error(parse("FLASER 2.5 1 1 0 0 0 0 0 0 1 h 1\n"), "aces.clf", 1,
                                 {"beam count n: expected an integer, found '2.5'"}));
}

TEST(CarmenReader, RejectsNegativeRange) {
  EXPECT_TRUE(throws_input_error(parse("FLASER 3 1 -0.5 2 0 0 0 0 0 0 1 h 1\n"), "aces.clf", 1,
                                 {"FLASER", "range 2 of 3", "non-negative", "'-0.5'"}));
}

TEST(CarmenReader, RejectsTimestampsGoingBackwardsWithinARecordType) {
  for (const std::string tag :
       {"ODOM 0 0 0 0 0 0", "FLASER 1 1 0 0 0 0 0 0", "TRUEPOS 0 0 0 0 0 0", "ENCODER 1 2", "COMPASS 0"}) {
    const std::string text = tag + " 5 h 5\nSONAR 1 2\n" + tag + " 4.5 h 6\n";
    const std::string type = tag.substr(0, tag.find(' '));
    EXPECT_TRUE(throws_input_error(parse(text), "aces.clf", 3,
                                   {type, "timestamp 4.5 goes back in time", "(line 1)", "has timestamp 5"}))
        << type;
  }
}

TEST(CarmenReader, RejectsEncoderTicksThatAreNotIntegers) {
  EXPECT_TRUE(throws_input_error(parse("ENCODER 1.5 2 1 h 1\n"), "aces.clf", 1,
                                 {"ENCODER", "left_ticks: expected an integer, found '1.5'"}));
  EXPECT_TRUE(throws_input_error(parse("ENCODER 1 99999999999999999999 1 h 1\n"), "aces.clf", 1,
                                 {"right_ticks: expected an integer"}));
}

TEST(CarmenReader, RejectsLinesThatDoNotStartWithARecordType) {
  EXPECT_TRUE(throws_input_error(parse(kGood + "12.5 0.3 1\n"), "aces.clf", 2,
                                 {"expected a record type such as ODOM", "'12.5'"}));
}

TEST(CarmenReader, RejectsParamWithWrongFieldCountOrBadLaserValue) {
  EXPECT_TRUE(
      throws_input_error(parse("PARAM a\n"), "aces.clf", 1, {"PARAM", "expected 2 fields (name value)", "found 1"}));
  EXPECT_TRUE(throws_input_error(parse("PARAM robot_front_laser_max -3\n"), "aces.clf", 1,
                                 {"robot_front_laser_max", "positive maximum range"}));
  EXPECT_TRUE(throws_input_error(parse("PARAM robot_frontlaser_offset abc\n"), "aces.clf", 1,
                                 {"robot_frontlaser_offset", "expected a finite number"}));
}

TEST(CarmenReader, RejectsEmptyFile) {
  EXPECT_TRUE(throws_input_error(parse(""), "aces.clf", 0, {"empty file"}));
  EXPECT_TRUE(throws_input_error(parse("\n  \n\t\n"), "aces.clf", 0, {"empty file"}));
  ScratchDir dir;
  write_bytes(dir.file("empty.clf"), "");
  EXPECT_TRUE(throws_input_error([&] { read_carmen_log(dir.file("empty.clf")); }, "empty.clf", 0, {"empty file"}));
  write_bytes(dir.file("empty.clf.gz"), gzip(""));
  EXPECT_TRUE(
      throws_input_error([&] { read_carmen_log(dir.file("empty.clf.gz")); }, "empty.clf.gz", 0, {"empty file"}));
}

TEST(CarmenReader, RejectsMissingFileAndFolder) {
  ScratchDir dir;
  EXPECT_TRUE(throws_input_error([&] { read_carmen_log(dir.file("nope.clf")); }, "nope.clf", 0,
                                 {"cannot open", "no such file"}));
  EXPECT_TRUE(throws_input_error([&] { read_carmen_log(dir.path()); }, dir.path().string(), 0,
                                 {"is a folder", "regular file"}));
}

// A valid multi-line log compressed, then cut short by k bytes: never read as a short log.
TEST(CarmenReader, RejectsTruncatedGzipForEveryCutLength) {
  ScratchDir dir;
  std::string text;
  for (int i = 0; i < 200; ++i) {
    text += fmt::format("ODOM {} 0 0 0 0 0 {} h 0\n", i, i);
  }
  const std::string packed = gzip(text);
  for (std::size_t cut : {1u, 2u, 4u, 7u, 8u, 9u, 20u, 100u, 500u}) {
    ASSERT_LT(cut, packed.size() - 10);
    const auto path = dir.file(fmt::format("cut{}.clf.gz", cut));
    write_bytes(path, packed.substr(0, packed.size() - cut));
    try {
      read_carmen_log(path);
      ADD_FAILURE() << "truncated gzip (cut " << cut << " bytes) accepted";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_GT(e.line(), 0u);  // the line being read when the data ran out
      EXPECT_EQ(msg.rfind(fmt::format("{}:{}: ", path.string(), e.line()), 0), 0u) << msg;
      EXPECT_NE(msg.find("truncated gzip stream"), std::string::npos) << msg;
    }
  }
}

// Every prefix of a .clf.gz, down to the first byte, is rejected.
TEST(CarmenReader, RejectsEveryTruncationOfAGzipFile) {
  ScratchDir dir;
  std::string text;
  for (int i = 0; i < 40; ++i) text += fmt::format("ENCODER {} -3 {} h 0\n", i * 7, i);
  const std::string packed = gzip(text);
  const auto path = dir.file("prefix.clf.gz");
  for (std::size_t len = 1; len < packed.size(); ++len) {
    write_bytes(path, packed.substr(0, len));
    EXPECT_THROW(read_carmen_log(path), InputError) << "prefix of " << len << " bytes accepted";
  }
  write_bytes(path, packed);
  EXPECT_EQ(read_carmen_log(path).encoders.size(), 40u);
}

TEST(CarmenReader, RejectsCorruptGzipData) {
  ScratchDir dir;
  std::string text;
  for (int i = 0; i < 200; ++i) text += fmt::format("COMPASS 0.{} {} h 0\n", i, i);
  std::string packed = gzip(text);
  packed[packed.size() - 6] = static_cast<char>(packed[packed.size() - 6] ^ 0x55);  // CRC / length
  write_bytes(dir.file("bad.clf.gz"), packed);
  try {
    read_carmen_log(dir.file("bad.clf.gz"));
    FAIL() << "corrupt gzip accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.clf.gz"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gzip"), std::string::npos) << e.what();
  }
}

TEST(RelationsReader, RejectsWrongFieldCountAndBadNumbersWithFileAndLine) {
  EXPECT_TRUE(throws_input_error([] { parse_relations("1 2 0 0 0 0 0 0\n1 2 3\n", "a.relations"); }, "a.relations", 2,
                                 {"expected 8 fields, found 3"}));
  EXPECT_TRUE(throws_input_error([] { parse_relations("# c\n1 2 0 0 0 0 0 zz\n", "a.relations"); }, "a.relations", 2,
                                 {"yaw: expected a finite number, found 'zz'"}));
  EXPECT_TRUE(throws_input_error([] { parse_relations("1 2 nan 0 0 0 0 0\n", "a.relations"); }, "a.relations", 1,
                                 {"x: expected a finite number"}));
}

TEST(LogLoader, RejectsUnknownFormatsListingTheAcceptedOnes) {
  ScratchDir dir;
  write_bytes(dir.file("a.csv"), "1,2\n");
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("a.csv").string()); }, "a.csv", 0,
                                 {"unrecognised log format", "CARMEN", ".clf", ".relations", "MRCLAM"}));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.path().string()); }, dir.path().string(), 0,
                                 {"not an MRCLAM dataset folder", "accepted: a CARMEN log"}));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("a.csv").string() + "#robot2"); }, "a.csv#robot2", 0,
                                 {"needs an MRCLAM dataset folder"}));
  EXPECT_TRUE(throws_input_error([&] { load_log(dir.file("missing.clf").string()); }, "missing.clf", 0,
                                 {"no such file or folder"}));
}

}  // namespace
}  // namespace locbench::io
