// The order of a relations file's lines is not information: the diagnosis sorts the relations
// by time, so a reversed or shuffled file gives the same windows and the same verdict.
#include <gtest/gtest.h>

#include <algorithm>

#include "algorithms/diagnosis/diagnosis.h"
#include "datasets/diagnosis/hidden_effects.h"

namespace locbench::diagnosis {
namespace {

TEST(RelationOrder, ReversingTheRelationsChangesNothing) {
  sim::GeneratorOptions o;
  o.reference = sim::GeneratedReference::kRelations;
  o.velocity_odometry = true;
  o.compass = false;
  o.waypoints = 6;
  Log log = sim::generate_log({{"wheel_diameter_ratio", 0.01}}, 3, o).log;
  ASSERT_GT(log.relations.size(), 10u);
  const Diagnosis forward = diagnose_log(log);
  std::reverse(log.relations.begin(), log.relations.end());
  const Diagnosis reversed = diagnose_log(log);
  EXPECT_EQ(reversed.verdict, forward.verdict);
  EXPECT_EQ(reversed.detected, forward.detected);
  ASSERT_EQ(reversed.residual_tests.size(), forward.residual_tests.size());
  for (std::size_t i = 0; i < forward.residual_tests.size(); ++i) {
    EXPECT_EQ(reversed.residual_tests[i].value, forward.residual_tests[i].value) << forward.residual_tests[i].name;
  }
}

}  // namespace
}  // namespace locbench::diagnosis
