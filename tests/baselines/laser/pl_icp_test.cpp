// PL-ICP (Censi 2008) and point-to-point ICP: recover known motions between ray-cast scans,
// keep the first guess along a corridor, and report a covariance that matches the spread.
#include "baselines/laser/pl_icp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/angle.h"
#include "core/errors.h"
#include "laser_scenes.h"

namespace locbench::baselines::laser {
namespace {

using test::lms_scan, test::segments_map;

// A 8 m × 6 m room with a box, so every direction is observable.
LineMap room() {
  return segments_map(
      {{0, 0, 8, 0}, {8, 0, 8, 6}, {8, 6, 0, 6}, {0, 6, 0, 0}, {4, 2, 5, 2}, {5, 2, 5, 3}, {5, 3, 4, 3}, {4, 3, 4, 2}});
}

// Two 30 m parallel walls 2 m apart: the position along them is not observable.
LineMap corridor() { return segments_map({{-15, -1, 15, -1}, {-15, 1, 15, 1}}); }

struct Pair {
  Scan first, second;
  Pose2 motion;  // true second pose in the first robot frame
};

Pair scans(const LineMap& world, const Pose2& a, const Pose2& b, double sigma, std::uint64_t seed) {
  return {lms_scan(world, a, sigma, seed), lms_scan(world, b, sigma, seed + 1000), between(a, b)};
}

TEST(PlIcp, RecoversAKnownMotionFromAGuessOffBy10CmAnd3Degrees) {
  const Pair p = scans(room(), Pose2(2.0, 1.5, deg(20)), Pose2(2.4, 1.7, deg(28)), 0.005, 1);
  const Pose2 guess = p.motion * Pose2(0.10, -0.08, deg(3));
  struct Case {
    IcpMetric metric;
    int line_points;
    double metres, degrees;
  };
  // Point-to-point pairs points that are not the same surface point (1° beams): it is biased by
  // a fraction of the beam spacing, PL-ICP is not.
  for (const Case c : {Case{IcpMetric::kPointToLine, 5, 0.005, 0.1}, Case{IcpMetric::kPointToLine, 2, 0.005, 0.1},
                       Case{IcpMetric::kPointToPoint, 5, 0.02, 0.5}}) {
    PlIcpOptions o;
    o.metric = c.metric;
    o.line_points = c.line_points;
    const PlIcpResult r = pl_icp(p.first, p.second, guess, o);
    ASSERT_TRUE(r.valid) << to_string(c.metric);
    EXPECT_TRUE(r.converged) << to_string(c.metric);
    EXPECT_FALSE(r.degenerate);
    EXPECT_LT(translation_distance(r.motion, p.motion), c.metres) << to_string(c.metric) << c.line_points;
    EXPECT_LT(std::abs(angle_diff(r.motion.theta, p.motion.theta)), deg(c.degrees))
        << to_string(c.metric) << c.line_points;
  }
}

TEST(PlIcp, PointToLineNeedsFewerIterationsThanPointToPoint) {
  // Censi 2008's claim: quadratic vs linear convergence.
  const Pair p = scans(room(), Pose2(2.0, 1.5, deg(20)), Pose2(2.4, 1.7, deg(28)), 0.0, 2);
  const Pose2 guess = p.motion * Pose2(0.10, -0.08, deg(3));
  PlIcpOptions line, point;
  point.metric = IcpMetric::kPointToPoint;
  const auto a = pl_icp(p.first, p.second, guess, line);
  const auto b = pl_icp(p.first, p.second, guess, point);
  EXPECT_LT(a.iterations, b.iterations);
  EXPECT_LT(a.iterations, 15);
}

TEST(PlIcp, KeepsTheFirstGuessAlongACorridorAndFixesTheRest) {
  // The first robot frame is aligned with the walls, so "along" is its x axis.
  const Pair p = scans(corridor(), Pose2(0.0, 0.2, 0.0), Pose2(0.5, 0.1, deg(3)), 0.005, 3);
  const Pose2 guess(p.motion.x + 0.30, p.motion.y + 0.05, p.motion.theta + deg(2));
  const PlIcpResult r = pl_icp(p.first, p.second, guess, {});
  ASSERT_TRUE(r.valid);
  EXPECT_TRUE(r.degenerate);
  EXPECT_LT(std::abs(angle_diff(r.motion.theta, p.motion.theta)), deg(0.2));
  EXPECT_NEAR(r.motion.y, p.motion.y, 0.01);  // across: fixed
  EXPECT_NEAR(r.motion.x, guess.x, 1e-3);     // along: the guess (0.3 m off), not invented
  EXPECT_TRUE(std::isinf(r.covariance(0, 0)));
  EXPECT_TRUE(std::isfinite(r.covariance(1, 1)));
}

TEST(PlIcp, CovarianceMatchesTheSpreadOverNoisyScans) {
  const Pose2 a(2.0, 1.5, deg(20)), b(2.3, 1.6, deg(25));
  const Pose2 truth = between(a, b);
  std::vector<Eigen::Vector3d> errors;
  Eigen::Matrix3d reported = Eigen::Matrix3d::Zero();
  const int n = 40;
  for (int k = 0; k < n; ++k) {
    const Pair p = scans(room(), a, b, 0.01, 100 + static_cast<std::uint64_t>(k));
    const PlIcpResult r = pl_icp(p.first, p.second, truth * Pose2(0.05, 0.03, deg(1)), {});
    ASSERT_TRUE(r.valid);
    errors.emplace_back(r.motion.x - truth.x, r.motion.y - truth.y, angle_diff(r.motion.theta, truth.theta));
    reported += r.covariance / n;
  }
  for (int i = 0; i < 3; ++i) {
    double ss = 0.0;
    for (const auto& e : errors) ss += e[i] * e[i];
    const double sample = ss / n;
    // The reported covariance counts both scans' noise (pl_icp.h); more than 4× off either way
    // would be wrong.
    EXPECT_GT(sample, 0.25 * reported(i, i)) << i;
    EXPECT_LT(sample, 4.0 * reported(i, i)) << i;
  }
}

TEST(PlIcp, TooFewPointsGivesTheGuessBackAsNotValid) {
  Scan empty;
  empty.bearings = {0.0};
  empty.ranges = {100.0};
  empty.max_range = 8.0;
  const Pose2 guess(0.1, 0.2, 0.3);
  const PlIcpResult r = pl_icp(empty, empty, guess, {});
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.motion.x, guess.x);
  EXPECT_EQ(r.motion.theta, guess.theta);
}

TEST(PlIcp, OptionsAreStrict) {
  PlIcpOptions o;
  EXPECT_THROW(from_json(nlohmann::json{{"keep_fraction", 0.0}}, o), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"metric", "point_to_plane"}}, o), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"no_such_option", 1}}, o), UsageError);
  nlohmann::json j;
  o.metric = IcpMetric::kPointToPoint;
  o.keep_fraction = 0.8;
  to_json(j, o);
  PlIcpOptions back;
  from_json(j, back);
  EXPECT_EQ(back.metric, IcpMetric::kPointToPoint);
  EXPECT_EQ(back.keep_fraction, 0.8);
  Scan s;
  EXPECT_THROW(pl_icp(s, s, Pose2(std::nan(""), 0, 0), {}), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::laser
