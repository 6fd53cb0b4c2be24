#include "algorithms/calibration/identifiability.h"

#include <gtest/gtest.h>

#include <cmath>

namespace locbench::calibration {
namespace {

TEST(Identifiability, AFullRankModelGivesTheLeastSquaresStandardErrors) {
  // y_i = a + b·x_i, x = 0, 1, 2, 3, σ = 0.1: Var(b) = σ²/Σ(x − x̄)² = 0.01/5.
  Eigen::MatrixXd J(4, 2);
  J << 1, 0, 1, 1, 1, 2, 1, 3;
  const Eigen::MatrixXd S = 0.01 * Eigen::MatrixXd::Identity(4, 4);
  const auto r = analyze_identifiability(J, S, {"a", "b"}, Eigen::Vector2d(1, 2));
  EXPECT_EQ(r.rank, 2);
  EXPECT_TRUE(r.parameters[0].identifiable);
  EXPECT_NEAR(r.parameters[1].standard_error, std::sqrt(0.01 / 5.0), 1e-12);
  EXPECT_TRUE(std::isfinite(r.condition_number));
}

TEST(Identifiability, ARatioOnlyModelLeavesBothParametersUndeterminedAndNamesTheCombination) {
  // Measurements depend on p − q only (linearised ratio): the direction (1, 1) is free.
  Eigen::MatrixXd J(3, 2);
  J << 1, -1, 2, -2, -1, 1;
  const auto r = analyze_identifiability(J, Eigen::MatrixXd::Identity(3, 3), {"E_b", "E_o"}, Eigen::Vector2d(1.0, 1.0));
  EXPECT_EQ(r.rank, 1);
  EXPECT_FALSE(r.parameters[0].identifiable);
  EXPECT_FALSE(r.parameters[1].identifiable);
  EXPECT_TRUE(std::isinf(r.parameters[0].standard_error));
  ASSERT_EQ(r.undetermined_combinations.size(), 1u);
  EXPECT_NE(r.undetermined_combinations[0].find("E_b"), std::string::npos);
  EXPECT_NE(r.parameters[0].reason.find("E_o"), std::string::npos);
  EXPECT_TRUE(std::isinf(r.condition_number));
}

TEST(Identifiability, AParameterThatNoMeasurementTouchesIsTheOnlyUndeterminedOne) {
  Eigen::MatrixXd J(2, 3);
  J << 1, 0, 0, 0, 1, 0;
  const auto r = analyze_identifiability(J, Eigen::MatrixXd::Identity(2, 2), {"a", "b", "c"}, Eigen::Vector3d(0, 0, 0));
  EXPECT_TRUE(r.parameters[0].identifiable);
  EXPECT_TRUE(r.parameters[1].identifiable);
  EXPECT_FALSE(r.parameters[2].identifiable);
}

}  // namespace
}  // namespace locbench::calibration
