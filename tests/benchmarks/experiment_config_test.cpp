#include <gtest/gtest.h>

#include "core/errors.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/experiment_options.h"

namespace locbench::experiments {
namespace {

TEST(MergeConfig, OverridesKnownKeysRecursivelyAndKeepsTheRest) {
  const nlohmann::json d = {{"runs", 20}, {"scenario", {{"speed", 0.25}, {"name", "corridor"}}}};
  const nlohmann::json m = merge_config(d, {{"scenario", {{"speed", 0.5}}}});
  EXPECT_EQ(m["runs"], 20);
  EXPECT_EQ(m["scenario"]["speed"], 0.5);
  EXPECT_EQ(m["scenario"]["name"], "corridor");
}

TEST(MergeConfig, RejectsAnUnknownKeyByItsPath) {
  const nlohmann::json d = {{"scenario", {{"speed", 0.25}}}};
  try {
    merge_config(d, {{"scenario", {{"sped", 0.5}}}});
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("scenario.sped"), std::string::npos) << e.what();
  }
}

TEST(MergeConfig, RejectsAValueOfTheWrongType) {
  EXPECT_THROW(merge_config({{"runs", 20}}, {{"runs", "many"}}), UsageError);
  EXPECT_NO_THROW(merge_config({{"speed", 0.25}}, {{"speed", 1}}));  // int where a double is
}

// An experiment's options as the experiments write them: scalars, lists, a list of objects, a raw
// JSON value and a nested struct.
struct ItemOptions {
  std::string name;
  double weight = 1.0;
};
template <class V>
void visit_fields(V& v, ItemOptions& o) {
  v.field("name", o.name, "", Range{}, "name");
  v.field("weight", o.weight, "kg", positive(), "weight");
}
LOCBENCH_EXPERIMENT_OPTIONS(ItemOptions)

struct SampleOptions {
  int runs = 3;
  std::vector<double> sizes_m = {0.5, 1.0};
  std::vector<std::string> names = {"a", "b"};
  std::vector<Eigen::Vector2d> path = {{0.0, 0.0}, {1.0, 2.0}};
  std::vector<ItemOptions> items = {{"x", 2.0}};
  nlohmann::json datasets = {"aces", {{"log", "my.clf"}}};
  ItemOptions main{"m", 3.0};
};
template <class V>
void visit_fields(V& v, SampleOptions& o) {
  v.field("runs", o.runs, "", at_least(1), "runs");
  v.field("sizes_m", o.sizes_m, "m", positive(), "sizes");
  v.field("names", o.names, "", Range{}, "names");
  v.field("path", o.path, "m", any_finite(), "path");
  v.field("items", o.items, "", Range{}, "items");
  v.field("datasets", o.datasets, "", Range{}, "datasets");
  v.nested("main", o.main, "main item");
}

std::string usage_error_of(const nlohmann::json& config) {
  try {
    read_options<SampleOptions>(config, "exp");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ExperimentOptions, DefaultsAreTheStructsAndReadBackUnchanged) {
  const nlohmann::json j = options_json(SampleOptions{});
  EXPECT_EQ(j.at("runs"), 3);
  EXPECT_EQ(j.at("sizes_m"), nlohmann::json({0.5, 1.0}));
  EXPECT_EQ(j.at("path"), nlohmann::json({{0.0, 0.0}, {1.0, 2.0}}));
  EXPECT_EQ(j.at("items"), nlohmann::json({{{"name", "x"}, {"weight", 2.0}}}));
  EXPECT_EQ(j.at("datasets"), nlohmann::json({"aces", {{"log", "my.clf"}}}));
  EXPECT_EQ(j.at("main"), nlohmann::json({{"name", "m"}, {"weight", 3.0}}));
  EXPECT_EQ(options_json(read_options<SampleOptions>(j, "exp")).dump(), j.dump());
}

TEST(ExperimentOptions, ReadsListsObjectsAndRawValues) {
  nlohmann::json j = options_json(SampleOptions{});
  j["sizes_m"] = {2.0, 3.0, 4.0};
  j["path"] = {{5.0, 6.0}};
  j["items"] = {{{"name", "y"}}, {{"name", "z"}, {"weight", 0.5}}};
  j["datasets"] = {"intel"};
  const SampleOptions o = read_options<SampleOptions>(j, "exp");
  EXPECT_EQ(o.sizes_m, (std::vector<double>{2.0, 3.0, 4.0}));
  ASSERT_EQ(o.path.size(), 1u);
  EXPECT_EQ(o.path[0], Eigen::Vector2d(5.0, 6.0));
  ASSERT_EQ(o.items.size(), 2u);
  EXPECT_EQ(o.items[0].weight, 1.0);  // absent key: the item's default
  EXPECT_EQ(o.items[1].weight, 0.5);
  EXPECT_EQ(o.datasets, nlohmann::json({"intel"}));
}

TEST(ExperimentOptions, RejectUnknownKeysWrongTypesAndRangesNamingTheKey) {
  EXPECT_NE(usage_error_of({{"runz", 3}}).find("exp.runz: unknown key"), std::string::npos)
      << usage_error_of({{"runz", 3}});
  EXPECT_NE(usage_error_of({{"runs", 2.5}}).find("exp.runs: expected an integer"), std::string::npos);
  EXPECT_NE(usage_error_of({{"runs", 0}}).find("exp.runs: expected ≥ 1"), std::string::npos);
  EXPECT_NE(usage_error_of({{"sizes_m", {1.0, "two"}}}).find("exp.sizes_m[1]: expected a number"), std::string::npos);
  EXPECT_NE(usage_error_of({{"sizes_m", {1.0, -2.0}}}).find("exp.sizes_m: expected each > 0 m"), std::string::npos);
  EXPECT_NE(usage_error_of({{"names", "a"}}).find("exp.names: expected an array"), std::string::npos);
  EXPECT_NE(usage_error_of({{"path", {{1.0}}}}).find("exp.path[0]: expected an array of 2 numbers"), std::string::npos);
  const std::string item = usage_error_of({{"items", {{{"name", "y"}, {"weight", -1.0}}}}});
  EXPECT_NE(item.find("exp.items[0]: ItemOptions.weight: expected > 0 kg"), std::string::npos) << item;
  const std::string nested = usage_error_of({{"main", {{"colour", 1}}}});
  EXPECT_NE(nested.find("exp.main: ItemOptions.colour: unknown key"), std::string::npos) << nested;
}

TEST(ExperimentOptions, DescribeEveryFieldForTheDocs) {
  const std::vector<FieldDoc> rows = describe_options<SampleOptions>();
  EXPECT_EQ(rows.size(), 7u);
  const std::string table = fields_markdown(rows);
  EXPECT_NE(table.find("sizes_m"), std::string::npos);
  EXPECT_NE(table.find("list; each item a number, > 0"), std::string::npos) << table;
}

// Every registered experiment reads its own defaults back, and refuses a whole-number option
// given as a fraction (which merge_config lets through: both are numbers).
TEST(ExperimentOptions, EveryExperimentReadsItsDefaultsAndRejectsAFractionalRunCount) {
  for (const auto& e : all_experiments()) {
    nlohmann::json config = e->default_config();
    if (!config.contains("runs")) continue;
    RunOptions o;
    EXPECT_GE(e->task_count(config, o), 1) << e->name();
    config["runs"] = 1.5;
    EXPECT_THROW(e->task_count(config, o), UsageError) << e->name();
  }
}

}  // namespace
}  // namespace locbench::experiments
