#include "algorithms/core/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace locbench {
namespace {

TEST(Moments, CentralMomentsOfASmallSample) {
  const std::vector<double> v{1, 2, 3, 4, 10};  // mean 4
  EXPECT_DOUBLE_EQ(mean(v), 4.0);
  EXPECT_DOUBLE_EQ(central_moment(v, 2), (9 + 4 + 1 + 0 + 36) / 5.0);
  EXPECT_DOUBLE_EQ(central_moment(v, 3), (-27 - 8 - 1 + 0 + 216) / 5.0);
  EXPECT_DOUBLE_EQ(sample_variance(v), 50.0 / 4.0);
}

TEST(Quantile, InterpolatesBetweenOrderStatisticsLikeNumPy) {
  const std::vector<double> v{3, 1, 2, 4};
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile(v, 0.25), 1.75);
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.0), 4.0);
}

TEST(StudentT, CriticalValuesMatchTheTable) {
  EXPECT_NEAR(student_t_critical(0.95, 1), 12.706, 1e-3);
  EXPECT_NEAR(student_t_critical(0.95, 4), 2.776, 1e-3);
  EXPECT_NEAR(student_t_critical(0.95, 9), 2.262, 1e-3);
  EXPECT_NEAR(student_t_critical(0.95, 1000), 1.962, 1e-3);
}

TEST(Normal, QuantileAndTail) {
  EXPECT_NEAR(normal_quantile(0.975), 1.959964, 1e-6);
  EXPECT_NEAR(normal_upper_tail(1.959964), 0.025, 1e-7);
}

TEST(Summarize, GivesAStudentTIntervalAroundTheMean) {
  const std::vector<double> v{10, 12, 9, 11, 13, 10, 12, 11, 10, 12};  // n = 10
  const Summary s = summarize(v);
  EXPECT_EQ(s.n, 10u);
  EXPECT_DOUBLE_EQ(s.mean, 11.0);
  const double half = 2.262157 * s.stddev / std::sqrt(10.0);
  EXPECT_NEAR(s.ci95_low, 11.0 - half, 1e-5);
  EXPECT_NEAR(s.ci95_high, 11.0 + half, 1e-5);
  EXPECT_DOUBLE_EQ(s.min, 9);
  EXPECT_DOUBLE_EQ(s.max, 13);
}

TEST(Summarize, OfOneValueHasAZeroWidthInterval) {
  const std::vector<double> v{4.2};
  const Summary s = summarize(v);
  EXPECT_DOUBLE_EQ(s.ci95_low, 4.2);
  EXPECT_DOUBLE_EQ(s.ci95_high, 4.2);
}

TEST(Summarize, RejectsAnEmptySample) {
  EXPECT_THROW(summarize(std::vector<double>{}), std::invalid_argument);
}

}  // namespace
}  // namespace locbench

namespace locbench {
namespace {

TEST(MannWhitney, CompletelySeparatedSamplesOfThreeGiveTheExactOneInTwenty) {
  // 3 + 3 values: C(6, 3) = 20 orderings; all a above all b happens once → p = 0.05.
  const std::vector<double> a{4, 5, 6}, b{1, 2, 3};
  const MannWhitneyResult r = mann_whitney_u(a, b);
  EXPECT_TRUE(r.exact);
  EXPECT_DOUBLE_EQ(r.u, 9.0);
  EXPECT_NEAR(r.p_greater, 0.05, 1e-12);
  EXPECT_NEAR(r.p_less, 1.0, 1e-12);
  EXPECT_NEAR(r.p_two_sided, 0.10, 1e-12);
}

TEST(MannWhitney, InterleavedSamplesAreNotSignificant) {
  const std::vector<double> a{1, 3, 5, 7}, b{2, 4, 6, 8};
  const MannWhitneyResult r = mann_whitney_u(a, b);
  EXPECT_DOUBLE_EQ(r.u, 6.0);  // 0 + 1 + 2 + 3
  EXPECT_GT(r.p_two_sided, 0.5);
}

TEST(MannWhitney, LargeSamplesUseTheNormalApproximation) {
  // a = 1..20, b = 11..30.
  std::vector<double> a, b;
  for (int i = 1; i <= 20; ++i) a.push_back(i);
  for (int i = 11; i <= 30; ++i) b.push_back(i);
  const MannWhitneyResult r = mann_whitney_u(a, b);
  EXPECT_FALSE(r.exact);  // ties between the samples (11..20)
  // Pairs a > b: a = 12..20 beat 1..9 of b = 11..19 → Σ_{k=1}^{9} k = 45; 10 ties × ½ = 5.
  EXPECT_DOUBLE_EQ(r.u, 50.0);
  EXPECT_LT(r.p_less, 0.001);  // a is clearly smaller
}

}  // namespace
}  // namespace locbench
