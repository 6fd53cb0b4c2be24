#include "core/rng.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/statistics.h"

namespace locbench {
namespace {

TEST(Rng, SameSeedGivesTheSameSequence) {
  Rng a(42), b(42);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.normal(), b.normal());
}

TEST(Rng, StreamsOfOneSeedDiffer) {
  Rng a = Rng::stream(42, 0), b = Rng::stream(42, 1);
  EXPECT_NE(a.uniform(), b.uniform());
}

TEST(Rng, NormalHasUnitVarianceAndZeroMean) {
  Rng r(7);
  std::vector<double> v(200000);
  for (double& x : v) x = r.normal();
  EXPECT_NEAR(mean(v), 0.0, 0.01);  // 4.5 standard errors
  EXPECT_NEAR(central_moment(v, 2), 1.0, 0.01);
  EXPECT_NEAR(central_moment(v, 4), 3.0, 0.06);
}

TEST(Rng, UniformCoversZeroToOne) {
  Rng r(9);
  double lo = 1, hi = 0, sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const double u = r.uniform();
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);
}

TEST(Rng, StudentTHasTheVarianceOfItsDegreesOfFreedom) {
  Rng r(11);
  std::vector<double> v;
  for (int i = 0; i < 200000; ++i) v.push_back(r.student_t(6.0));
  EXPECT_NEAR(central_moment(v, 2), 6.0 / 4.0, 0.05) << "ν/(ν − 2)";
  std::vector<double> z;
  for (int i = 0; i < 100000; ++i) z.push_back(r.student_t(0.0));
  EXPECT_NEAR(central_moment(z, 2), 1.0, 0.02) << "dof 0 is the normal law";
}

}  // namespace
}  // namespace locbench
