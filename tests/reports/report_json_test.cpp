#include "reports/report_json.h"

#include <gtest/gtest.h>

#include <fstream>

#include "algorithms/core/errors.h"
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
  {
    std::ofstream(path) << to_json(testing::sample_report()).dump().substr(0, 100);
  }
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

}  // namespace
}  // namespace locbench::reports
