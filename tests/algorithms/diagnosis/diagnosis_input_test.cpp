// Bad input gets a clear error (what was expected), never a verdict; the thesis's Table 3.1
// histogram is diagnosed as a quantized residual.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "core/units.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "diagnosis_test_helpers.h"
#include "tests/input_error_message.h"
#include "tests/options_error_message.h"

namespace locbench::diagnosis {
namespace {

using testing::input_error_message;

TEST(DiagnoseInput, ALogWithoutReferenceIsAnErrorNotAVerdict) {
  sim::GeneratorOptions o;
  o.compass = false;
  Log log = sim::generate_log({}, 1, o).log;
  log.truth.clear();
  const std::string e = input_error_message([&] { diagnose_log(log); });
  EXPECT_NE(e.find("no reference"), std::string::npos) << e;
  EXPECT_NE(e.find("TRUEPOS"), std::string::npos) << e;
}

TEST(DiagnoseInput, ALogWithoutOdometryIsAnError) {
  Log log = sim::generate_log({}, 1).log;
  log.encoders.clear();
  EXPECT_NE(input_error_message([&] { diagnose_log(log); }).find("no odometry"), std::string::npos);
}

TEST(DiagnoseInput, TooShortALogIsAnError) {
  Log log = sim::generate_log({}, 1).log;
  log.encoders.resize(100);  // 10 s of encoders: 10 windows
  const std::string e = input_error_message([&] { diagnose_log(log); });
  EXPECT_NE(e.find("too short"), std::string::npos) << e;
}

TEST(DiagnoseInput, AWheelbaseInMillimetresIsAnError) {
  Log log = sim::generate_log({}, 1).log;
  log.params[kParamWheelbase] = "381.97";
  const std::string e = input_error_message([&] { diagnose_log(log); });
  EXPECT_NE(e.find("robot_wheelbase"), std::string::npos) << e;
  EXPECT_NE(e.find("mm"), std::string::npos) << e;
}

TEST(DiagnoseInput, ACompassResolutionInDegreesIsAnError) {
  Log log = sim::generate_log({}, 1).log;
  log.params["compass_resolution"] = "2";
  EXPECT_NE(input_error_message([&] { diagnose_log(log); }).find("compass_resolution"), std::string::npos);
}

TEST(DiagnoseInput, MalformedHistogramsNameWhatWasExpected) {
  test_support::expect_histogram_errors({
      {R"({"residual": "r", "unit": "deg", "edges": [0, 1, 2], "counts": [1, 2, 3]})", "one edge more"},
      {R"({"residual": "r", "unit": "furlong", "edges": [0,1,2,3,4,5], "counts": [9,9,9,9,9]})", "unit"},
      {R"({"residual": "r", "unit": "deg", "edges": [0,1,2,3,4,5], "counts": [9,9,-9,9,9]})", "counts[2]"},
      {R"({"residual": "r", "unit": "deg", "edges": [0,1,1,3,4,5], "counts": [9,9,9,9,9]})", "edges[2]"},
      {R"({"residual": "r", "unit": "deg", "edges": [0,1,2,3,4,5], "counts": [1,1,1,1,1]})", "too few"},
      {R"({"unit": "deg", "edges": [0,1,2,3,4,5], "counts": [9,9,9,9,9]})", "residual"},
      {R"([1, 2])", "object"},
  });
  const auto err = test_support::histogram_error;
  EXPECT_EQ(err(R"({"residual": "r", "unit": "deg", "edges": [0,1,2,3,4,5], "counts": [9,9,9,9,9], "bins": 5})"),
            "h.json: bins: unknown key (expected one of: residual, unit, edges, counts, source)");
  EXPECT_EQ(err(R"({"residual": 1, "unit": "deg", "edges": [0,1,2,3,4,5], "counts": [9,9,9,9,9]})"),
            "h.json: residual: expected a string, found number");
}

TEST(DiagnosisOptions, WrongTypesUnknownKeysAndOutOfRangeValuesAreNamed) {
  const auto err = testing::options_error_message<DiagnosisOptions>;
  // A string used to escape as a library exception ("internal error").
  EXPECT_EQ(err({{"false_alarm", "1%"}}), "DiagnosisOptions.false_alarm: expected a number, found string");
  EXPECT_EQ(err({{"false_alarm", 0.5}}), "DiagnosisOptions.false_alarm: expected a number in (0, 0.5), got 0.5");
  EXPECT_EQ(err({{"holdout_block", 0}}), "DiagnosisOptions.holdout_block: expected ≥ 1, got 0");
  EXPECT_EQ(
      err({{"window", 1.0}}).rfind("DiagnosisOptions.window: unknown key (expected one of: false_alarm, window_s,", 0),
      0u);
  DiagnosisOptions o;
  from_json({{"window_s", 2.0}, {"rpe_chain", 5}}, o);
  EXPECT_EQ(o.windows.duration, 2.0);
  EXPECT_EQ(o.rpe_chain, 5u);
}

TEST(DiagnoseHistogram, Table3_1IsAQuantizedResidualOnA2DegreeLattice) {
  const char* root = std::getenv("LOCBENCH_SOURCE_DIR");
  std::ifstream in(std::string(root ? root : ".") + "/examples/table_3_1_histogram.json");
  ASSERT_TRUE(in);
  const auto h = read_histogram(nlohmann::json::parse(in), "table_3_1");
  const Diagnosis d = diagnose_histogram(h, "table_3_1");
  ASSERT_EQ(d.detected, std::vector<std::string>{"compass_quantization"}) << d.verdict;
  const Cause& q = d.causes.front();
  // The thesis's compass reports multiples of 2° (§3.4): the lattice step must be 2°.
  EXPECT_NEAR(to_deg(q.parameters.front().value), 2.0, 0.1);
  EXPECT_LT(to_deg(q.parameters.front().lo), 2.0);
  EXPECT_GT(to_deg(q.parameters.front().hi), 2.0);
  EXPECT_GT(q.gains.front().relative(), 0.0);
  // The thesis's own normality test accepts this sample at α = 0.1 (|u1| = 0.146, |u2| = 1.764).
  for (const auto& t : d.residual_tests) {
    if (t.name == "normality_skewness") {
      EXPECT_NEAR(std::abs(t.value), 0.14557, 2e-3);
    }
    if (t.name == "normality_kurtosis") {
      EXPECT_NEAR(std::abs(t.value), 1.76361, 2e-3);
    }
  }
}

TEST(DiagnoseHistogram, AZeroMeanNormalHistogramHasNoDiscrepancy) {
  // Counts of N(0, 1.5°) in 1° bins, 800 samples (rounded expected counts).
  ResidualHistogram h{"r", "deg", {}, {}};
  for (int i = -5; i <= 5; ++i) h.edges.push_back(deg(i));
  for (double c : {3, 15, 51, 117, 176, 176, 117, 51, 15, 3}) h.counts.push_back(c);
  const Diagnosis d = diagnose_histogram(h, "normal");
  EXPECT_TRUE(d.detected.empty()) << d.verdict;
  EXPECT_NE(d.verdict.find("No significant discrepancy"), std::string::npos) << d.verdict;
}

}  // namespace
}  // namespace locbench::diagnosis
