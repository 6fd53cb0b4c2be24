#include "reports/report_json.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "reports/schema_validation.h"
#include "tests/reports/sample_report.h"
#include "tests/test_data.h"

namespace locbench::reports {
namespace {

TEST(ReportJson, SampleReportIsValidAgainstTheSchema) {
  const nlohmann::json j = to_json(testing::sample_report());
  const auto errors = validate_report_json(j);
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(j["schema"], "locbench.report/1");
  EXPECT_EQ(j["results"][0]["name"], "odometry_nominal/sim_corridor/final_position_error");
  EXPECT_EQ(j["published"][0]["rows"][1]["ours"], nullptr);
}

TEST(ReportJson, AnUndeterminedEstimateIsFlaggedWithItsReason) {
  const nlohmann::json j = to_json(testing::sample_report());
  const nlohmann::json& e = j["results"][1];
  EXPECT_EQ(e["name"], "umbmark_improved/sim_trilobot/E_o");
  EXPECT_EQ(e["identifiable"], false);
  EXPECT_EQ(e["note"], "only E_o/E_b is determined by the square");
  EXPECT_EQ(e["over"], "estimate");
}

TEST(MakeEstimate, GivesANormalIntervalFromTheStandardError) {
  const MetricResult m = make_estimate("ml", "sim", "wheelbase", "m", 0.2, 0.001, 50);
  EXPECT_NEAR(m.summary.ci95_low, 0.2 - 1.96 * 0.001, 1e-6);
  EXPECT_NEAR(m.summary.ci95_high, 0.2 + 1.96 * 0.001, 1e-6);
  EXPECT_FALSE(m.identifiable.has_value());
}

TEST(ReportJson, SchemaRejectsAReportWithoutProvenance) {
  nlohmann::json j = to_json(testing::sample_report());
  j["context"].erase("git_revision");
  EXPECT_FALSE(validate_report_json(j).empty());
}

TEST(ReportJson, SchemaRejectsAnUnstableResultName) {
  nlohmann::json j = to_json(testing::sample_report());
  j["results"][0]["name"] = "no-slashes";
  EXPECT_FALSE(validate_report_json(j).empty());
}

TEST(ReportJson, SchemaRejectsABadChecksumAndAnEmptyResult) {
  nlohmann::json j = to_json(testing::sample_report());
  j["datasets"][0]["checksum"] = "md5:xyz";
  j["results"][0]["n"] = 0;
  EXPECT_GE(validate_report_json(j).size(), 2u);
}

TEST(ReportJson, RoundTripsThroughAFile) {
  testing::ScratchDir dir;
  const Report r = testing::sample_report();
  const auto path = write_report(r, dir.file("sub/report.json"));
  const Report back = read_report(path);
  EXPECT_EQ(to_json(back), to_json(r));
}

TEST(ReportJson, ReadingAWrongSchemaNamesTheFileAndTheExpectation) {
  testing::ScratchDir dir;
  nlohmann::json j = to_json(testing::sample_report());
  j["schema"] = "other/2";
  try {
    report_from_json(j, "x.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("locbench.report/1"), std::string::npos);
  }
}

TEST(ReportJson, ReadingTruncatedJsonIsAnInputError) {
  testing::ScratchDir dir;
  const auto path = dir.file("r.json");
  { std::ofstream(path) << to_json(testing::sample_report()).dump().substr(0, 100); }
  EXPECT_THROW(read_report(path), InputError);
}

TEST(ReportJson, MissingFieldIsNamed) {
  nlohmann::json j = to_json(testing::sample_report());
  j["results"][0].erase("unit");
  try {
    report_from_json(j, "r.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"unit\""), std::string::npos) << e.what();
  }
}

TEST(ReportJson, PlotsThreadsAndShardsRoundTripAndValidate) {
  Report r = testing::sample_report();
  r.provenance.threads = 3;
  r.provenance.shards = 4;
  r.body.plots.push_back({"error_vs_distance",
                          "error_vs_distance",
                          "Error",
                          "distance travelled",
                          "m",
                          "position error",
                          "m",
                          {{"odometry_nominal", {0.0, 0.25, 0.5}, {0.0, 0.01, 0.03}}},
                          "mean over 3 runs"});
  const nlohmann::json j = to_json(r);
  const auto errors = validate_report_json(j);
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(j["context"]["threads"], 3);
  EXPECT_EQ(j["plots"][0]["x"]["unit"], "m");
  const Report back = report_from_json(j, "r.json");
  EXPECT_EQ(back.provenance.shards, 4);
  ASSERT_EQ(back.body.plots.size(), 1u);
  EXPECT_EQ(back.body.plots[0].series[0].y, (std::vector<double>{0.0, 0.01, 0.03}));
  EXPECT_EQ(to_json(back), j);
}

TEST(ReportJson, SchemaRejectsAPlotOfUnknownKind) {
  Report r = testing::sample_report();
  r.body.plots.push_back({"p", "pie", "t", "x", "", "y", "", {}, ""});
  EXPECT_FALSE(validate_report_json(to_json(r)).empty());
}

TEST(ReportJson, ResultsRoundTripExactlyWithoutTheContext) {
  const ExperimentResults b = testing::sample_report().body;
  const nlohmann::json j = results_to_json(b);
  EXPECT_FALSE(j.contains("context"));
  EXPECT_EQ(results_to_json(results_from_json(j, "x")), j);
}

}  // namespace
}  // namespace locbench::reports

namespace locbench::reports {
namespace {

// The findings' fields (tolerances, checks, diagnosed logs) survive a round trip, and a report
// without them (every report written before) still loads with them empty.
TEST(ReportJson, FindingsFieldsRoundTripAndAreOptional) {
  Report r = testing::sample_report();
  PublishedComparison c{"thesis Table X", "error", "mm", {{"a", 1.0, 1.1}}, "note"};
  c.rows[0].check = 1.2;
  c.rows[0].tolerance = 0.3;
  c.rows[0].compared = false;
  c.claim = "the error is 1 mm";
  c.tolerance = 0.5;
  c.relative_tolerance = 0.01;
  c.tolerance_basis = "printed digits";
  r.body.published = {c};
  r.body.diagnoses = {
      {"log1",
       "TRUEPOS",
       {{"velocity_scale", {{"scale", 1.02, 1.01, 1.03}}, FindingGain{"translation_rms", 0.2, 0.1}, true}},
       "one cause"}};
  const Report back = report_from_json(to_json(r), "mem");
  ASSERT_EQ(back.body.published.size(), 1u);
  const PublishedComparison& b = back.body.published[0];
  EXPECT_EQ(b.claim, "the error is 1 mm");
  EXPECT_EQ(b.tolerance, 0.5);
  EXPECT_EQ(b.relative_tolerance, 0.01);
  EXPECT_EQ(b.tolerance_basis, "printed digits");
  EXPECT_EQ(b.rows[0].check, 1.2);
  EXPECT_EQ(b.rows[0].tolerance, 0.3);
  EXPECT_FALSE(b.rows[0].compared);
  ASSERT_EQ(back.body.diagnoses.size(), 1u);
  const DiagnosedLog& d = back.body.diagnoses[0];
  EXPECT_EQ(d.log, "log1");
  ASSERT_EQ(d.causes.size(), 1u);
  EXPECT_EQ(d.causes[0].parameters[0].hi, 1.03);
  ASSERT_TRUE(d.causes[0].gain);
  EXPECT_EQ(d.causes[0].gain->after, 0.1);

  nlohmann::json old = to_json(testing::sample_report());
  ASSERT_FALSE(old.contains("diagnoses"));
  const Report loaded = report_from_json(old, "old");
  EXPECT_TRUE(loaded.body.diagnoses.empty());
  for (const auto& p : loaded.body.published) EXPECT_FALSE(p.tolerance);
  EXPECT_TRUE(validate_report_json(to_json(r)).empty());
}

}  // namespace
}  // namespace locbench::reports
