#include "reports/shard_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/errors.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "tests/reports/sample_report.h"
#include "tests/test_data.h"

namespace locbench::reports {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

ShardReport sample_shard() {
  ShardReport s;
  s.provenance = testing::sample_report().provenance;
  s.provenance.threads = 2;
  s.experiment = "odometry/sim_corridor";
  s.description = "dead reckoning";
  s.configuration = {{"runs", 5}};
  s.seed = 7;
  s.runs = 5;
  s.index = 2;
  s.count = 3;
  s.tasks = 5;
  s.records = {{1, {{"error", 0.1 + 0.2}, {"nees", {1.0, kNaN, kInf}}}}, {4, {{"error", 1e-300}, {"nees", {-kInf}}}}};
  return s;
}

TEST(NonFinite, NaNAndInfinitiesSurviveTheJsonTextWhichWouldOtherwiseMakeThemNull) {
  const nlohmann::json record = {{"a", kNaN}, {"b", {1.5, kInf, -kInf}}, {"c", "text"}};
  EXPECT_EQ(nlohmann::json::parse(record.dump())["a"], nullptr);  // why encoding is needed
  const nlohmann::json back = canonical_record(record);
  EXPECT_TRUE(std::isnan(back["a"].get<double>()));
  EXPECT_EQ(back["b"][0].get<double>(), 1.5);
  EXPECT_EQ(back["b"][1].get<double>(), kInf);
  EXPECT_EQ(back["b"][2].get<double>(), -kInf);
  EXPECT_EQ(back["c"], "text");
  EXPECT_EQ(encode_nonfinite(record)["b"][1], (nlohmann::json{{"nonfinite", "inf"}}));
}

TEST(NonFinite, EveryFiniteDoubleReadsBackBitForBit) {
  for (double v : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, 4.9e-324, -2.2250738585072014e-308}) {
    EXPECT_EQ(canonical_record(nlohmann::json(v)).get<double>(), v);
  }
}

TEST(ShardReportJson, RoundTripsThroughItsSchemaValidText) {
  testing::ScratchDir dir;
  const ShardReport s = sample_shard();
  const nlohmann::json j = to_json(s);
  const auto errors = validate_shard_json(j);
  EXPECT_TRUE(errors.empty()) << errors.front();
  write_shard_report(s, dir.file("a/x.shard-2-of-3.json"));
  const ShardReport back = read_shard_report(dir.file("a/x.shard-2-of-3.json"));
  EXPECT_EQ(back.experiment, "odometry/sim_corridor");
  EXPECT_EQ(back.seed, 7u);
  EXPECT_EQ(back.runs, 5);
  EXPECT_EQ(back.index, 2);
  EXPECT_EQ(back.count, 3);
  EXPECT_EQ(back.tasks, 5);
  EXPECT_EQ(back.provenance.threads, 2);
  ASSERT_EQ(back.records.size(), 2u);
  EXPECT_EQ(back.records[1].task, 4);
  EXPECT_EQ(back.records[0].record["error"].get<double>(), 0.1 + 0.2);
  EXPECT_TRUE(std::isnan(back.records[0].record["nees"][1].get<double>()));
  EXPECT_EQ(back.records[1].record["nees"][0].get<double>(), -kInf);
}

TEST(ShardReportJson, RunsAreNullWhenNotGivenOnTheCommandLine) {
  ShardReport s = sample_shard();
  s.runs.reset();
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(j["runs"], nullptr);
  EXPECT_TRUE(validate_shard_json(j).empty());
  EXPECT_FALSE(shard_report_from_json(j, "x").runs.has_value());
}

TEST(ShardReportJson, AFullReportIsRejectedAsNotAShard) {
  const nlohmann::json report = to_json(testing::sample_report());
  EXPECT_FALSE(validate_shard_json(report).empty());
  try {
    shard_report_from_json(report, "r.json");
    FAIL() << "accepted a report as a shard";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a full report, not a shard"), std::string::npos) << e.what();
  }
}

TEST(ShardReportJson, SchemaRejectsAShardWithoutItsIndex) {
  nlohmann::json j = to_json(sample_shard());
  j["shard"].erase("index");
  EXPECT_FALSE(validate_shard_json(j).empty());
  EXPECT_THROW(shard_report_from_json(j, "x"), InputError);
}

}  // namespace
}  // namespace locbench::reports
