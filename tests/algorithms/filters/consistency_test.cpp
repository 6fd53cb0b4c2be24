#include "algorithms/filters/consistency.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "core/rng.h"
#include "core/units.h"

namespace locbench::filters {
namespace {

TEST(Consistency, NeesAndNisOfHandCases) {
  const Eigen::Vector3d e(1.0, 2.0, 0.5);
  const Eigen::Matrix3d p = Eigen::Vector3d(1.0, 4.0, 0.25).asDiagonal();
  EXPECT_NEAR(nees(e, p), 1.0 + 1.0 + 1.0, 1e-14);
  Eigen::Matrix2d c;
  c << 2.0, 1.0, 1.0, 2.0;  // inverse = [2 −1; −1 2]/3
  EXPECT_NEAR(nees(Eigen::Vector2d(1.0, 1.0), c), (2.0 - 1.0 - 1.0 + 2.0) / 3.0, 1e-14);
  EXPECT_EQ(nees(e, Eigen::Matrix3d::Zero()), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(nis(0.3, 0.09), 1.0, 1e-14);
  EXPECT_EQ(nis(0.3, 0.0), std::numeric_limits<double>::infinity());
  EXPECT_THROW(nees(e, Eigen::Matrix2d::Identity()), std::invalid_argument);
}

TEST(Consistency, PoseNeesWrapsTheHeadingError) {
  const Pose2 truth(1.0, 1.0, deg(179.0));
  const Eigen::Matrix3d p = Eigen::Vector3d(1.0, 1.0, deg(1.0) * deg(1.0)).asDiagonal();
  EXPECT_NEAR(pose_nees(truth, Eigen::Vector3d(1.0, 1.0, deg(-179.0)), p), 4.0, 1e-9);
}

TEST(Consistency, ChiSquareBoundsMatchTables) {
  // χ²₁: 2.5% and 97.5% points 0.000982 and 5.0239.
  const ChiSquareInterval one = average_chi_square_interval(1, 1);
  EXPECT_NEAR(one.lower, 0.000982069, 1e-8);
  EXPECT_NEAR(one.upper, 5.023886, 1e-5);
  // χ²(150)/50 for a 3-state filter over 50 runs: [117.985, 185.800]/50.
  const ChiSquareInterval fifty = average_chi_square_interval(3, 50);
  EXPECT_NEAR(fifty.lower * 50.0, 117.985, 2e-3);
  EXPECT_NEAR(fifty.upper * 50.0, 185.800, 2e-3);
  EXPECT_TRUE(fifty.contains(3.0));
  EXPECT_FALSE(fifty.contains(4.0));
  EXPECT_THROW(average_chi_square_interval(0, 5), std::invalid_argument);
  EXPECT_THROW(average_chi_square_interval(3, 5, 1.0), std::invalid_argument);
}

TEST(Consistency, GaussianErrorsWithTheirTrueCovarianceAreConsistent) {
  Eigen::Matrix3d p;
  p << 4e-4, 1e-4, 2e-5,  //
      1e-4, 3e-4, -1e-5,  //
      2e-5, -1e-5, 1e-4;
  const Eigen::Matrix3d l = p.llt().matrixL();
  Rng rng(5);
  const int runs = 50, steps = 200;
  std::vector<std::vector<double>> good(runs), bad(runs);
  for (int r = 0; r < runs; ++r) {
    for (int k = 0; k < steps; ++k) {
      const Eigen::Vector3d e = l * Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal());
      good[r].push_back(nees(e, p));
      bad[r].push_back(nees(e, 0.5 * p));  // claims half the true covariance
    }
  }
  const ConsistencySummary g = summarize_consistency(good, 3);
  EXPECT_EQ(g.runs, 50u);
  EXPECT_EQ(g.steps, 200u);
  EXPECT_NEAR(g.time_average, 3.0, 0.05);
  EXPECT_GT(g.fraction_inside, 0.9);
  const ConsistencySummary b = summarize_consistency(bad, 3);
  EXPECT_NEAR(b.time_average, 6.0, 0.1);
  EXPECT_GT(b.fraction_above, 0.95);
  EXPECT_NEAR(b.fraction_inside + b.fraction_above + b.fraction_below, 1.0, 1e-12);
}

TEST(Consistency, SummaryRejectsRaggedOrEmptyInput) {
  EXPECT_THROW(summarize_consistency({}, 3), std::invalid_argument);
  EXPECT_THROW(summarize_consistency({{1.0, 2.0}, {1.0}}, 3), std::invalid_argument);
  const ConsistencySummary s = summarize_consistency({{3.0, 100.0}, {3.0, 100.0}}, 3);
  EXPECT_DOUBLE_EQ(s.average[0], 3.0);
  EXPECT_DOUBLE_EQ(s.fraction_inside, 0.5);
  EXPECT_DOUBLE_EQ(s.fraction_above, 0.5);
}

}  // namespace
}  // namespace locbench::filters
