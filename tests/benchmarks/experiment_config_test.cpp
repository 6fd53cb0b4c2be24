#include <gtest/gtest.h>

#include "core/errors.h"
#include "benchmarks/experiments/framework/experiment.h"

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

}  // namespace
}  // namespace locbench::experiments
