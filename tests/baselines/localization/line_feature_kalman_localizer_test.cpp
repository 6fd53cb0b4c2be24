#include "baselines/localization/line_feature_kalman_localizer.h"

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

#include <cmath>
#include <limits>
#include <vector>

#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"
#include "tests/algorithms/pose_correction/ray_cast_matches.h"

namespace locbench::baselines::localization {
namespace {

using Eigen::Vector3d;

// The robot's true pose in the room and its wheelbase [m] in the tests below.
const Pose2 kTruth{2.0, 1.0, deg(46.0)};
constexpr double kWheelbase = 0.33;

LineFeatureKalmanOptions with_p0(const Vector3d& p0) {
  LineFeatureKalmanOptions o;
  o.initial_covariance = p0;
  return o;
}

// The diagonal prior covariance of standard deviations `sigma_xy` [m] in x and y, `sigma_theta` [rad].
Vector3d prior(double sigma_xy, double sigma_theta) {
  return {sigma_xy * sigma_xy, sigma_xy * sigma_xy, std::pow(sigma_theta, 2)};
}

// A localizer of the default options starting at `start` with the prior covariance `p0`.
LineFeatureKalmanLocalizer localizer_at(const Pose2& start, const Vector3d& p0) {
  return LineFeatureKalmanLocalizer(with_p0(p0), kWheelbase, start);
}

// Observations of the room from `truth` (5 mm noise): lines fitted to the robot-frame points
// of each segment really hit.
std::vector<LineObservation> observe(const LineMap& map, const Pose2& truth, Rng& rng) {
  const auto scan = test::ray_cast_scan(map, truth, &rng);
  return line_observations(test::matches_by_true_hit(scan, truth));
}

TEST(ValidationGate, IsTheChiSquareQuantileWithTwoDegreesOfFreedom) {
  EXPECT_NEAR(validation_gate(0.99), 9.21034, 1e-5);
  EXPECT_NEAR(validation_gate(0.95), 5.99146, 1e-5);
  EXPECT_THROW(validation_gate(1.0), UsageError);
}

TEST(LineFeatureKalmanLocalizer, GateRejectsAnOutlierLineAndLeavesTheEstimateAsWithout) {
  const LineMap room = sim::room_world();
  const Pose2 start{2.05, 0.97, deg(44.0)};
  Rng rng(4);
  const auto obs = observe(room, kTruth, rng);
  ASSERT_GE(obs.size(), 5u);
  // A line no map segment explains: 0.4 m in front of the robot, facing it (a person).
  std::vector<LineObservation> with_outlier = obs;
  LineObservation ghost;
  ghost.alpha = 0.0;
  ghost.r = 0.4;
  ghost.covariance = Eigen::Vector2d(std::pow(deg(1.0), 2), 1e-4).asDiagonal();
  with_outlier.push_back(ghost);

  LineFeatureKalmanLocalizer a = localizer_at(start, prior(0.05, deg(3.0)));
  LineFeatureKalmanLocalizer b = localizer_at(start, prior(0.05, deg(3.0)));
  const LineUpdate ua = a.update(obs, room);
  const LineUpdate ub = b.update(with_outlier, room);
  EXPECT_EQ(ua.pairs.size(), obs.size());
  EXPECT_TRUE(ua.unmatched.empty());
  ASSERT_EQ(ub.unmatched.size(), 1u);
  EXPECT_EQ(ub.unmatched[0], obs.size());
  EXPECT_TRUE(a.mean().isApprox(b.mean(), 1e-15));
  // Every accepted pair is inside g² and paired with the segment really seen.
  for (const auto& p : ub.pairs) EXPECT_LE(p.mahalanobis2, ub.gate);
}

TEST(LineFeatureKalmanLocalizer, PairsEachObservationWithTheSegmentItCameFrom) {
  const LineMap room = sim::room_world();
  Rng rng(8);
  const auto scan = test::ray_cast_scan(room, kTruth, &rng);
  const auto matches = test::matches_by_true_hit(scan, kTruth);
  const auto obs = line_observations(matches);
  ASSERT_EQ(obs.size(), matches.size());
  LineFeatureKalmanLocalizer loc = localizer_at(Pose2{2.08, 0.95, deg(43.0)}, {0.01, 0.01, 0.003});
  const LineUpdate u = loc.associate(obs, room);
  ASSERT_EQ(u.pairs.size(), obs.size());
  for (const auto& p : u.pairs) EXPECT_EQ(p.map_segment, matches[p.observation].map_segment);
}

TEST(LineFeatureKalmanLocalizer, StackedUpdateWithFullInnovationCovarianceEqualsSequentialUpdates) {
  // h is affine in the pose, so one update with Σ_IN = ∇h Σ_p ∇hᵀ + blockdiag(Σ_R) must equal
  // the updates one line at a time. (The slides' block-diagonal Σ_IN would not.)
  const LineMap room = sim::room_world();
  const Pose2 start{2.1, 1.1, deg(43.0)};
  Rng rng(2);
  const auto obs = observe(room, kTruth, rng);
  LineFeatureKalmanLocalizer batch = localizer_at(start, prior(0.1, deg(4.0)));
  LineFeatureKalmanLocalizer seq = localizer_at(start, prior(0.1, deg(4.0)));
  const LineUpdate ub = batch.update(obs, room);
  ASSERT_EQ(ub.pairs.size(), obs.size());
  for (const auto& p : ub.pairs) {
    const std::vector<LineObservation> one{obs[p.observation]};
    ASSERT_EQ(seq.update(one, room).pairs.size(), 1u);
  }
  EXPECT_TRUE(batch.mean().isApprox(seq.mean(), 1e-9));
  EXPECT_TRUE(batch.covariance().isApprox(seq.covariance(), 1e-6));
}

TEST(LineFeatureKalmanLocalizer, ConvergesOnTheRoomFromAWrongStart) {
  // Start 0.15 m and 4° off with a prior that covers it; the robot drives 2 m along its heading
  // at 0.2 m/s (5 Hz), odometry with 0.2% wheel-diameter error, one scan per step.
  const LineMap room = sim::room_world();
  Pose2 truth = kTruth;
  LineFeatureKalmanLocalizer loc = localizer_at(Pose2{2.1, 1.1, deg(42.0)}, prior(0.15, deg(5.0)));
  Rng rng(21);
  double first_error = 0.0;
  for (int k = 0; k < 50; ++k) {
    const WheelDisplacement ground{0.04, 0.04};
    truth = odometry_step(truth, ground, kWheelbase);
    loc.predict({0.04 * 1.001, 0.04 * 0.999});
    const LineUpdate u = loc.update(observe(room, truth, rng), room);
    EXPECT_GE(u.pairs.size(), 3u) << k;
    if (k == 0) first_error = translation_distance(loc.pose(), truth);
  }
  EXPECT_LT(first_error, 0.05);
  EXPECT_LT(translation_distance(loc.pose(), truth), mm(10.0));
  EXPECT_LT(std::abs(angle_diff(loc.pose().theta, truth.theta)), deg(0.2));
  // The claimed uncertainty covers the error (NEES below χ²₃(0.999) = 16.3).
  const Vector3d e{truth.x - loc.mean()(0), truth.y - loc.mean()(1), angle_diff(truth.theta, loc.mean()(2))};
  EXPECT_LT(e.dot(loc.covariance().ldlt().solve(e)), 16.3);
}

TEST(LineFeatureKalmanLocalizer, RejectsInvalidInput) {
  EXPECT_THROW(LineFeatureKalmanLocalizer({}, -1.0, Pose2{}), UsageError);
  LineFeatureKalmanOptions o;
  o.gate_probability = 0.0;
  EXPECT_THROW(LineFeatureKalmanLocalizer(o, kWheelbase, Pose2{}), UsageError);
  LineFeatureKalmanLocalizer loc({}, kWheelbase, Pose2{});
  LineObservation bad;
  bad.r = std::numeric_limits<double>::quiet_NaN();
  const std::vector<LineObservation> obs{bad};
  EXPECT_THROW(loc.update(obs, sim::room_world()), UsageError);
  EXPECT_THROW((nlohmann::json{{"gate", 9.21}}.get<LineFeatureKalmanOptions>()), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::localization
