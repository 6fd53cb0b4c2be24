#include "baselines/localization/line_observation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"

namespace locbench::baselines::localization {
namespace {

using Eigen::Vector2d;

TEST(LineObservation, WallInFrontHasAlphaNinetyAndCovarianceFromTheFit) {
  // Robot-frame points on y = 2 at x = −1, 0, 1 (noise-free → σ floored at 5 mm).
  const std::vector<Vector2d> pts{{-1, 2}, {0, 2}, {1, 2}};
  const LineObservation z = line_observation(pts);
  EXPECT_NEAR(z.alpha, deg(90.0), 1e-12);
  EXPECT_NEAR(z.r, 2.0, 1e-12);
  const double s2 = 25e-6;
  EXPECT_NEAR(z.covariance(0, 0), s2 / 2.0, 1e-15);  // σ²/Σt²
  EXPECT_NEAR(z.covariance(1, 1), s2 / 3.0, 1e-15);  // σ²/N, centroid at the foot (t_c = 0)
  EXPECT_NEAR(z.covariance(0, 1), 0.0, 1e-15);
}

TEST(LineObservation, OffCentreSegmentCorrelatesAlphaAndR) {
  // Points at x = 1, 2, 3 on y = 2: t_c = (−sin α, cos α)·c = −2, so a tilt of the line moves r:
  // var r = σ²/N + 4 var α, cov(α, r) = −2 var α.
  const std::vector<Vector2d> pts{{1, 2}, {2, 2}, {3, 2}};
  const LineObservation z = line_observation(pts);
  const double va = 25e-6 / 2.0;
  EXPECT_NEAR(z.covariance(0, 0), va, 1e-15);
  EXPECT_NEAR(z.covariance(0, 1), -2.0 * va, 1e-15);
  EXPECT_NEAR(z.covariance(1, 1), 25e-6 / 3.0 + 4.0 * va, 1e-15);
}

TEST(LineObservation, CovarianceMatchesTheScatterOfNoisyFits) {
  // 2000 fits of 30 points on x cos 60° + y sin 60° = 3 (an off-centre stretch), σ = 1 cm.
  const double a = deg(60.0), r = 3.0;
  const Vector2d n(std::cos(a), std::sin(a)), d(-std::sin(a), std::cos(a));
  Rng rng(11);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum2 = Eigen::Matrix2d::Zero(), predicted = Eigen::Matrix2d::Zero();
  const int runs = 2000;
  for (int k = 0; k < runs; ++k) {
    std::vector<Vector2d> pts;
    for (int i = 0; i < 30; ++i) {
      pts.push_back(r * n + (0.5 + 0.05 * i) * d + rng.normal(0.0, 0.01) * n);
    }
    const LineObservation z = line_observation(pts, 1e-6);
    const Eigen::Vector2d e(angle_diff(z.alpha, a), z.r - r);
    sum += e;
    sum2 += e * e.transpose();
    predicted += z.covariance / runs;
  }
  const Eigen::Matrix2d cov = (sum2 - sum * sum.transpose() / runs) / (runs - 1);
  EXPECT_NEAR(cov(0, 0) / predicted(0, 0), 1.0, 0.1);
  EXPECT_NEAR(cov(1, 1) / predicted(1, 1), 1.0, 0.1);
  EXPECT_NEAR(cov(0, 1) / predicted(0, 1), 1.0, 0.15);
}

TEST(LineObservation, RejectsDegenerateInput) {
  const std::vector<Vector2d> one{{1, 2}};
  const std::vector<Vector2d> same{{1, 2}, {1, 2}};
  EXPECT_THROW(line_observation(one), UsageError);
  EXPECT_THROW(line_observation(same), UsageError);
  const std::vector<Vector2d> ok{{1, 2}, {2, 2}};
  EXPECT_THROW(line_observation(ok, 0.0), UsageError);
}

// h(pose) by finite differences against the slides' ∇h (with the flip when r < 0).
void expect_jacobian_matches_finite_differences(const LineParams& line, const Pose2& pose) {
  const LinePrediction h = predict_line(line, pose);
  const double eps = 1e-6;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d dp = Eigen::Vector3d::Zero();
    dp(c) = eps;
    const LinePrediction hp = predict_line(line, Pose2{pose.x + dp(0), pose.y + dp(1), pose.theta + dp(2)});
    const LinePrediction hm = predict_line(line, Pose2{pose.x - dp(0), pose.y - dp(1), pose.theta - dp(2)});
    ASSERT_EQ(hp.flipped, h.flipped);
    ASSERT_EQ(hm.flipped, h.flipped);
    const double da = angle_diff(hp.z(0), hm.z(0)) / (2 * eps);
    const double dr = (hp.z(1) - hm.z(1)) / (2 * eps);
    EXPECT_NEAR(h.jacobian(0, c), da, 1e-7) << "column " << c;
    EXPECT_NEAR(h.jacobian(1, c), dr, 1e-7) << "column " << c;
  }
}

TEST(PredictLine, SlidesJacobianMatchesFiniteDifferences) {
  // Robot on the origin's side of the line: r > 0, ∇h = [[0, 0, −1], [−cos β, −sin β, 0]].
  const LineParams line{5.0, deg(30.0)};
  const Pose2 pose{1.0, 0.5, deg(20.0)};
  const LinePrediction h = predict_line(line, pose);
  EXPECT_FALSE(h.flipped);
  EXPECT_NEAR(h.z(0), deg(10.0), 1e-12);
  EXPECT_NEAR(h.z(1), 5.0 - (std::cos(deg(30.0)) + 0.5 * std::sin(deg(30.0))), 1e-12);
  EXPECT_NEAR(h.jacobian(1, 0), -std::cos(deg(30.0)), 1e-15);
  expect_jacobian_matches_finite_differences(line, pose);
}

TEST(PredictLine, BeyondTheLineRIsFlippedAndSoIsTheJacobiansRRow) {
  // Block B's right face x = 6 (β = 0, ρ = 6) seen from x = 7: ρ − x = −1 → (α + π, 1).
  const LineParams line{6.0, 0.0};
  const Pose2 pose{7.0, 5.0, deg(170.0)};
  const LinePrediction h = predict_line(line, pose);
  EXPECT_TRUE(h.flipped);
  EXPECT_NEAR(h.z(1), 1.0, 1e-12);
  EXPECT_NEAR(angle_diff(h.z(0), kPi - deg(170.0)), 0.0, 1e-12);
  EXPECT_NEAR(h.jacobian(1, 0), 1.0, 1e-15);  // +cos β, not −cos β
  expect_jacobian_matches_finite_differences(line, pose);
  // And the flipped prediction is what the laser really observes: fit the face's points.
  const Pose2 inv = pose.inverse();
  std::vector<Eigen::Vector2d> pts;
  for (double y = 4.2; y <= 5.8; y += 0.1) pts.push_back(inv * Eigen::Vector2d(6.0, y));
  const LineObservation z = line_observation(pts);
  EXPECT_NEAR(line_innovation(z, h).norm(), 0.0, 1e-9);
}

TEST(PredictLine, RandomPosesAgreeWithFiniteDifferences) {
  Rng rng(9);
  for (int k = 0; k < 50; ++k) {
    const LineParams line{rng.uniform(0.5, 8.0), rng.uniform(-kPi, kPi)};
    const Pose2 pose{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-kPi, kPi)};
    if (std::abs(predict_line(line, pose).z(1)) < 0.01) continue;  // on the line: no normal form
    expect_jacobian_matches_finite_differences(line, pose);
  }
}

}  // namespace
}  // namespace locbench::baselines::localization
