// The verdict of a published table is computed from its numbers and the tolerance it states.
#include "reports/findings.h"

#include <gtest/gtest.h>

namespace locbench::reports {
namespace {

PublishedComparison table(std::vector<PublishedRow> rows, std::optional<double> tolerance) {
  PublishedComparison c;
  c.source = "thesis Table X";
  c.quantity = "error";
  c.unit = "mm";
  c.rows = std::move(rows);
  c.tolerance = tolerance;
  return c;
}

TEST(TableFinding, EveryRowWithinToleranceIsReproduced) {
  const TableFinding f = table_finding(table({{"a", 10.0, 10.4}, {"b", 20.0, 19.5}}, 0.5));
  EXPECT_EQ(f.verdict, Verdict::kReproduced);
  EXPECT_EQ(f.compared, 2u);
  EXPECT_EQ(f.within, 2u);
  EXPECT_EQ(f.reason, "all 2 rows within ±0.5 mm");
}

TEST(TableFinding, ARowOutsideToleranceIsNotReproducedAndTheReasonNamesIt) {
  const TableFinding f = table_finding(table({{"a", 10.0, 10.4}, {"b", 20.0, 23.0}}, 0.5));
  EXPECT_EQ(f.verdict, Verdict::kNotReproduced);
  EXPECT_EQ(f.within, 1u);
  EXPECT_NE(f.reason.find("b: ours 23 vs published 20 mm (off by 3, tolerance 0.5)"), std::string::npos) << f.reason;
}

TEST(TableFinding, OursConfirmedAnotherWayMakesTheThesisWrong) {
  PublishedRow r{"sigma", 5.00, 5.518};
  r.check = 5.5184;  // e.g. the closed form beside the numerical optimum
  const TableFinding f = table_finding(table({r, {"b", 1.0, 1.01}}, 0.05));
  EXPECT_EQ(f.verdict, Verdict::kThesisWrong);
  EXPECT_EQ(f.thesis_wrong, 1u);
  EXPECT_NE(f.reason.find("computed another way: 5.518"), std::string::npos) << f.reason;
}

TEST(TableFinding, ACheckThatAgreesWithThePublishedFigureDoesNotBlameTheThesis) {
  PublishedRow r{"sigma", 5.00, 5.518};
  r.check = 5.01;
  EXPECT_EQ(table_finding(table({r}, 0.05)).verdict, Verdict::kNotReproduced);
}

TEST(TableFinding, NoToleranceOrNoComparableRowGivesNoVerdict) {
  EXPECT_EQ(table_finding(table({{"a", 10.0, 10.0}}, std::nullopt)).verdict, Verdict::kNoVerdict);
  EXPECT_EQ(table_finding(table({{"a", std::nullopt, 10.0}}, 1.0)).verdict, Verdict::kNoVerdict);
}

TEST(TableFinding, RelativeAndPerRowTolerances) {
  PublishedComparison c = table({{"a", 100.0, 104.0}}, std::nullopt);
  c.relative_tolerance = 0.05;
  EXPECT_EQ(table_finding(c).verdict, Verdict::kReproduced);  // 4 ≤ 5% of 100
  c.rows[0].tolerance = 1.0;                                  // the row's own, tighter
  EXPECT_EQ(table_finding(c).verdict, Verdict::kNotReproduced);
}

TEST(CompareMeansOnly, LeavesUnpairedRunsOutAndUsesThePublishedRunsSpread) {
  PublishedComparison c = table({{"run 1", 10.0, 50.0}, {"run 2", 14.0, 1.0}, {"mean", 12.0, 14.0}}, std::nullopt);
  compare_means_only(c, {10.0, 14.0});
  ASSERT_TRUE(c.tolerance);
  EXPECT_NEAR(*c.tolerance, 2.8284271, 1e-6);  // sample SD of {10, 14}
  const TableFinding f = table_finding(c);
  EXPECT_EQ(f.compared, 1u);
  EXPECT_EQ(f.verdict, Verdict::kReproduced);  // |14 − 12| ≤ 2.83
}

}  // namespace
}  // namespace locbench::reports
