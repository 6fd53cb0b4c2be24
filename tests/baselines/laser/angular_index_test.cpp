#include "baselines/laser/angular_index.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/angle.h"
#include "core/rng.h"

namespace locbench::baselines::laser {
namespace {

// The nearest point within √max_d2 by checking every point.
bool brute_force(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q, double max_d2, double& d2) {
  d2 = std::numeric_limits<double>::infinity();
  for (const auto& p : points) d2 = std::min(d2, (p - q).squaredNorm());
  return d2 <= max_d2;
}

// 2,000 random scenes: a scan-like arc of points (a 180° or a full field of view, walls at 0.5–8 m,
// some points clustered at the origin) and queries anywhere, near and far, behind the scanner too.
TEST(AngularIndex, FindsTheSameNearestDistanceAsCheckingEveryPoint) {
  Rng rng(7);
  int compared = 0, found = 0;
  for (int scene = 0; scene < 2000; ++scene) {
    const bool full = scene % 2 == 0;
    const int n = 1 + static_cast<int>(rng.uniform(0.0, 200.0));
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < n; ++i) {
      const double a = full ? rng.uniform(-kPi, kPi) : rng.uniform(-0.5 * kPi, 0.5 * kPi);
      const double r = i % 17 == 0 ? rng.uniform(0.0, 0.01) : rng.uniform(0.5, 8.0);
      points.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    const AngularIndex index(points);
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector2d q(rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0));
      const double max_d2 = k % 3 == 0 ? std::numeric_limits<double>::infinity() : rng.uniform(0.0, 4.0);
      double want = 0.0, got = 0.0;
      std::size_t at = 0;
      const bool expected = brute_force(points, q, max_d2, want);
      ASSERT_EQ(index.nearest(q, max_d2, at, got), expected) << "scene " << scene << " query " << k;
      ++compared;
      if (!expected) continue;
      ++found;
      EXPECT_EQ(got, want) << "scene " << scene << " query " << k;
      EXPECT_EQ((points[at] - q).squaredNorm(), want);
    }
  }
  EXPECT_EQ(compared, 40000);
  EXPECT_GT(found, 10000);  // the bound on max_d2 is exercised both ways
}

TEST(AngularIndex, AnEmptyScanHasNoNearestPoint) {
  const std::vector<Eigen::Vector2d> none;
  std::size_t at = 0;
  double d2 = 0.0;
  EXPECT_FALSE(AngularIndex(none).nearest({1.0, 0.0}, 1e9, at, d2));
}

TEST(AngularIndex, APointExactlyAtTheLimitCounts) {
  const std::vector<Eigen::Vector2d> points{{2.0, 0.0}};
  std::size_t at = 7;
  double d2 = 0.0;
  EXPECT_TRUE(AngularIndex(points).nearest({1.0, 0.0}, 1.0, at, d2));
  EXPECT_EQ(at, 0u);
  EXPECT_EQ(d2, 1.0);
  EXPECT_FALSE(AngularIndex(points).nearest({1.0, 0.0}, 0.999, at, d2));
}

}  // namespace
}  // namespace locbench::baselines::laser
