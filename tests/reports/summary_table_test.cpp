#include "reports/summary_table.h"

#include <gtest/gtest.h>

#include "tests/reports/sample_report.h"

namespace locbench::reports {
namespace {

TEST(SummaryTable, ListsEachResultWithItsIntervalAndEachSkippedCase) {
  const std::string t = summary_table({testing::sample_report()});
  EXPECT_NE(t.find("odometry_nominal/sim_corridor/final_position_error"), std::string::npos);
  EXPECT_NE(t.find("0.1"), std::string::npos);
  EXPECT_NE(t.find("skipped: dataset not found"), std::string::npos);
}

}  // namespace
}  // namespace locbench::reports
