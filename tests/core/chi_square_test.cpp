#include "core/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace locbench {
namespace {

// Swapping the probability and the degrees of freedom does not compile.
static_assert(!std::is_invocable_v<decltype(&chi_square_quantile), double, ChiSquareDof>);
static_assert(!std::is_invocable_v<decltype(&chi_square_quantile), double, double>);

TEST(ChiSquare, QuantilesMatchTheTable) {
  EXPECT_NEAR(chi_square_quantile(ChiSquareDof(1.0), 0.95), 3.841459, 1e-6);
  EXPECT_NEAR(chi_square_quantile(ChiSquareDof(2.0), 0.99), 9.210340, 1e-6);
  EXPECT_NEAR(chi_square_quantile(ChiSquareDof(3.0), 0.99), 11.344867, 1e-6);
  EXPECT_NEAR(chi_square_quantile(ChiSquareDof(10.0), 0.025), 3.246973, 1e-6);
}

TEST(ChiSquare, UpperQuantileAndTailAreInverse) {
  EXPECT_NEAR(chi_square_upper_quantile(ChiSquareDof(1.0), 1e-3), 10.827566, 1e-6);
  EXPECT_NEAR(chi_square_upper_tail(ChiSquareDof(1.0), 3.841459), 0.05, 1e-7);
  EXPECT_NEAR(chi_square_upper_tail(ChiSquareDof(4.0), chi_square_upper_quantile(ChiSquareDof(4.0), 1e-12)), 1e-12,
              1e-20);
  EXPECT_EQ(chi_square_upper_tail(ChiSquareDof(2.0), 0.0), 1.0);
}

TEST(ChiSquare, TinyTailsStayFiniteOnTheComplement) {
  // 1 − 1e-300 rounds to 1: only the complement gives the threshold of a 1e-300 false alarm.
  const double x = chi_square_upper_quantile(ChiSquareDof(1.0), 1e-300);
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_GT(x, 1000.0);
}

TEST(ChiSquare, RejectsNonPositiveDofAndProbabilitiesOutsideTheRange) {
  EXPECT_THROW(ChiSquareDof(0.0), std::invalid_argument);
  EXPECT_THROW(ChiSquareDof(std::nan("")), std::invalid_argument);
  EXPECT_THROW(chi_square_quantile(ChiSquareDof(1.0), 1.0), std::invalid_argument);
  EXPECT_THROW(chi_square_upper_quantile(ChiSquareDof(1.0), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace locbench
