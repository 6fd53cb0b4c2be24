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
