// The UMBmark input a person fills in: what it reads, and a clear InputError naming the JSON
// field for every way it can be wrong.
#include "datasets/io/umbmark_input_reader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/errors.h"
#include "tests/test_data.h"

namespace locbench::io {
namespace {

// The Trilobot on the thesis's 1.6 m square: 1.6 m / (π·88.5 mm/22) = 126.6 → 127 counts a leg.
const std::string kValid = R"({
  "side_length_m": 1.6,
  "nominal": { "wheel_diameter_m": 0.0885, "wheelbase_m": 0.198,
               "gear_ratio": 1, "counts_per_rev": 22 },
  "tape_measure_scale": 1.002,
  "leg_ticks": { "left": 127, "right": 127 },
  "runs": [
    { "direction": "cw",  "x_error_m": 0.31,  "y_error_m": -0.12 },
    { "direction": "cw",  "x_error_m": 0.29,  "y_error_m": -0.10 },
    { "direction": "ccw", "x_error_m": -0.05, "y_error_m": 0.20 }
  ]
})";

// kValid with the first occurrence of `from` replaced by `to`.
std::string with(const std::string& from, const std::string& to) {
  std::string t = kValid;
  const auto at = t.find(from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "not in the sample: " << from;
    return t;
  }
  return t.replace(at, from.size(), to);
}

// Expects an InputError at `line` whose message contains every fragment.
void expect_error(const std::string& text, std::size_t line, std::initializer_list<std::string> fragments) {
  try {
    parse_umbmark_input(text, "umbmark.json");
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "umbmark.json");
    EXPECT_EQ(e.line(), line) << e.what();
    for (const auto& f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << "'" << f << "' not in: " << e.what();
    }
  }
}

TEST(UmbmarkInputReader, ReadsTheDocumentedFormatInMetres) {
  const UmbmarkInput in = parse_umbmark_input(kValid, "umbmark.json");
  EXPECT_EQ(in.side_length, 1.6);
  EXPECT_EQ(in.nominal.diameter_left, 0.0885);
  EXPECT_EQ(in.nominal.diameter_right, 0.0885);
  EXPECT_EQ(in.nominal.wheelbase, 0.198);
  EXPECT_EQ(in.encoder.gear_ratio, 1.0);
  EXPECT_EQ(in.encoder.counts_per_rev, 22.0);
  EXPECT_EQ(in.tape_measure_scale, 1.002);
  EXPECT_EQ(in.leg_ticks_left, 127);
  EXPECT_EQ(in.leg_ticks_right, 127);
  ASSERT_EQ(in.runs.size(), 3u);
  EXPECT_EQ(in.runs[0].direction, UmbmarkDirection::kClockwise);
  EXPECT_EQ(in.runs[0].x_error, 0.31);
  EXPECT_EQ(in.runs[0].y_error, -0.12);
  EXPECT_EQ(in.runs[2].direction, UmbmarkDirection::kCounterClockwise);
}

TEST(UmbmarkInputReader, AcceptsPerWheelDiametersAndDefaultsTheTapeScaleToOne) {
  const std::string text =
      with(R"("wheel_diameter_m": 0.0885,)", R"("wheel_diameter_left_m": 0.0885, "wheel_diameter_right_m": 0.0889,)");
  const UmbmarkInput in = parse_umbmark_input(text, "umbmark.json");
  EXPECT_EQ(in.nominal.diameter_left, 0.0885);
  EXPECT_EQ(in.nominal.diameter_right, 0.0889);
  const UmbmarkInput no_tape = parse_umbmark_input(with(R"("tape_measure_scale": 1.002,)", ""), "umbmark.json");
  EXPECT_EQ(no_tape.tape_measure_scale, 1.0);
}

TEST(UmbmarkInputReader, ReadsAFileAndNamesAnUnreadableOne) {
  testing::ScratchDir dir;
  const auto path = dir.file("umbmark.json").string();
  std::ofstream(path) << kValid;
  EXPECT_EQ(read_umbmark_input(path).runs.size(), 3u);
  try {
    read_umbmark_input(dir.file("missing.json").string());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos);
  }
}

TEST(UmbmarkInputReader, MissingRunsAreAnError) {
  const auto start = kValid.find(R"(,
  "runs")");
  std::string no_runs = kValid.substr(0, start) + "\n}";
  expect_error(no_runs, 0, {"runs", "missing field"});
  expect_error(with(R"("runs": [)", R"("runs": [ ], "x": [)"), 0, {"x", "unknown key"});
  const std::string empty = kValid.substr(0, kValid.find(R"("runs")")) + R"("runs": [] })";
  expect_error(empty, 0, {"runs", "is empty", "both directions"});
}

TEST(UmbmarkInputReader, ASingleDirectionIsAnError) {
  const std::string text = with(R"("direction": "ccw")", R"("direction": "cw")");
  expect_error(text, 0, {"runs", "3 clockwise and 0 counter-clockwise", "both directions"});
}

TEST(UmbmarkInputReader, NaNAndInfinityLiteralsAreRejectedWithTheirLine) {
  // NaN is on line 9 of the text (the second run's x error).
  expect_error(with("0.29", "NaN"), 9, {"'NaN' is not a JSON number", "finite"});
  expect_error(with("0.29", "-Infinity"), 9, {"'-Infinity'", "NaN and Infinity"});
  expect_error(with("0.29", "nan"), 9, {"'nan'"});
  // A literal beyond the double range.
  expect_error(with("0.29", "1e999"), 9, {"'1e999'", "finite"});
}

TEST(UmbmarkInputReader, NaNWrittenAsAStringIsRejectedByField) {
  expect_error(with("0.29", R"("NaN")"), 0, {"runs[1].x_error_m", "\"NaN\"", "NaN and Infinity are not allowed"});
  expect_error(with("1.6", R"("inf")"), 0, {"side_length_m", "\"inf\""});
}

TEST(UmbmarkInputReader, MillimetresWhereMetresBelongAreCaught) {
  expect_error(with("0.0885", "88.5"), 0, {"nominal.wheel_diameter_m", "looks like millimetres; expected metres"});
  expect_error(with("0.198", "198"), 0, {"nominal.wheelbase_m", "looks like millimetres"});
  // The side in mm makes the leg counts inconsistent too, but the side is checked first.
  expect_error(with("1.6", "1600"), 0, {"side_length_m", "looks like millimetres"});
  expect_error(with("0.31", "310"), 0, {"runs[0].x_error_m", "longer than the side", "looks like millimetres"});
  expect_error(with("-0.12", "-120"), 0, {"runs[0].y_error_m", "looks like millimetres"});
}

TEST(UmbmarkInputReader, LegCountsMustBeOneStraightLeg) {
  // The issue's example gives 57 counts: 57·12.638 mm = 0.720 m, not a 1.6 m leg.
  expect_error(with(R"("left": 127)", R"("left": 57)"), 0, {"leg_ticks.left", "57 counts are 0.720 m", "about 127"});
  expect_error(with(R"("right": 127)", R"("right": 126.5)"), 0, {"leg_ticks.right", "whole number"});
  expect_error(with(R"("right": 127)", R"("right": -127)"), 0, {"leg_ticks.right", "> 0"});
}

TEST(UmbmarkInputReader, WrongTypesNameTheFieldAndWhatWasFound) {
  expect_error(with("1.6", R"("1.6")"), 0, {"side_length_m", "expected a number in metres", "string \"1.6\""});
  expect_error(with(R"("direction": "cw")", R"("direction": 1)"), 0,
               {"runs[0].direction", "expected \"cw\" or \"ccw\"", "number"});
  expect_error(with(R"("direction": "cw")", R"("direction": "clockwise")"), 0, {"runs[0].direction", "\"clockwise\""});
  expect_error(with(R"("gear_ratio": 1)", R"("gear_ratio": true)"), 0, {"nominal.gear_ratio", "boolean"});
  expect_error(with(R"("leg_ticks": { "left": 127, "right": 127 })", R"("leg_ticks": [127, 127])"), 0,
               {"leg_ticks", "expected an object", "array"});
  const std::string runs_object = kValid.substr(0, kValid.find(R"("runs")")) + R"("runs": { "direction": "cw" } })";
  expect_error(runs_object, 0, {"runs", "expected an array", "object"});
  expect_error("[1, 2]", 0, {"expected an object", "array"});
}

TEST(UmbmarkInputReader, UnknownKeysAreErrorsAtEveryLevel) {
  expect_error(with(R"("side_length_m")", R"("side_m": 1, "side_length_m")"), 0,
               {"side_m", "unknown key", "side_length_m"});
  expect_error(with(R"("gear_ratio")", R"("gear": 1, "gear_ratio")"), 0, {"nominal.gear", "unknown key"});
  expect_error(with(R"("x_error_m": 0.29)", R"("x_err_m": 0.29)"), 0, {"runs[1].x_err_m", "unknown key", "x_error_m"});
}

TEST(UmbmarkInputReader, MissingFieldsAreNamed) {
  expect_error(with(R"("wheelbase_m": 0.198,)", ""), 0, {"nominal.wheelbase_m", "missing field"});
  expect_error(with(R"(,  "y_error_m": -0.10 )", ""), 0, {"runs[1].y_error_m", "missing field"});
}

TEST(UmbmarkInputReader, ImplausibleValuesAreRejected) {
  expect_error(with("0.0885", "0"), 0, {"nominal.wheel_diameter_m", "must be > 0"});
  expect_error(with("1.6", "-1.6"), 0, {"side_length_m", "must be > 0"});
  expect_error(with("1.002", "100.2"), 0, {"tape_measure_scale", "ratio near 1"});
  expect_error(with(R"("counts_per_rev": 22)", R"("counts_per_rev": 0)"), 0, {"nominal.counts_per_rev", "> 0"});
  expect_error(
      with(R"("wheel_diameter_m": 0.0885,)", R"("wheel_diameter_m": 0.0885, "wheel_diameter_left_m": 0.0885,)"), 0,
      {"nominal", "not both"});
}

TEST(UmbmarkInputReader, SyntaxErrorsCarryTheirLine) {
  expect_error(with(R"("leg_ticks": {)", R"("leg_ticks": {,)"), 6, {"invalid JSON"});
}

}  // namespace
}  // namespace locbench::io
