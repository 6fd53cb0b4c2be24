#include "core/diff_drive_odometry.h"

#include <gtest/gtest.h>

#include "tests/core/pose_matchers.h"

namespace locbench {
namespace {
using testing::IsNearlyPose;

constexpr double kB = 0.198;  // Trilobot-like wheelbase [m]

TEST(OdometryStep, EqualWheelsDriveStraight) {
  const Pose2 p = odometry_step(Pose2(1.0, 2.0, deg(90)), {0.1, 0.1}, kB);
  EXPECT_THAT(p, IsNearlyPose(Pose2(1.0, 2.1, deg(90)), 1e-12));
}

TEST(OdometryStep, OppositeWheelsTurnOnTheSpotByTwoUOverB) {
  const double u = kB * kPi / 4.0;  // Δθ = (U_R − U_L)/B = π/2
  const Pose2 p = odometry_step(Pose2(), {-u, u}, kB);
  EXPECT_THAT(p, IsNearlyPose(Pose2(0.0, 0.0, deg(90)), 1e-12));
}

TEST(OdometryStep, UsesTheMidpointHeadingOfEquation1_3) {
  // ΔD = 0.15, Δθ = 0.1/B; x' = ΔD cos(Δθ/2), y' = ΔD sin(Δθ/2).
  const Pose2 p = odometry_step(Pose2(), {0.1, 0.2}, kB);
  const double dth = 0.1 / kB;
  EXPECT_NEAR(p.x, 0.15 * std::cos(dth / 2), 1e-15);
  EXPECT_NEAR(p.y, 0.15 * std::sin(dth / 2), 1e-15);
  EXPECT_NEAR(p.theta, dth, 1e-15);
}

TEST(ExactArcStep, AQuarterCircleOfRadiusOneEndsOnTheCircle) {
  // Centre of the wheelbase on a circle of radius 1 m: U_L = (1 − B/2)·π/2, U_R = (1 + B/2)·π/2.
  const double q = kPi / 2.0;
  const Pose2 p = exact_arc_step(Pose2(), {(1.0 - kB / 2) * q, (1.0 + kB / 2) * q}, kB);
  EXPECT_THAT(p, IsNearlyPose(Pose2(1.0, 1.0, deg(90)), 1e-12));
}

TEST(ExactArcStep, AgreesWithTheMidpointStepOnAStraightLineAndTurningOnTheSpot) {
  EXPECT_THAT(exact_arc_step(Pose2(1.0, 2.0, deg(90)), {0.1, 0.1}, kB), IsNearlyPose(Pose2(1.0, 2.1, deg(90)), 1e-12));
  const double u = kB * kPi / 4.0;
  EXPECT_THAT(exact_arc_step(Pose2(), {-u, u}, kB), IsNearlyPose(Pose2(0.0, 0.0, deg(90)), 1e-12));
}

TEST(DisplacementFromTicks, ScalesEachWheelByItsMetresPerTick) {
  const NominalModel m{0.01264, 0.01270, kB};
  const WheelDisplacement u = displacement_from_ticks(m, 10, -3);
  EXPECT_DOUBLE_EQ(u.left, 0.1264);
  EXPECT_DOUBLE_EQ(u.right, -0.0381);
}

// Jacobians against central finite differences.
TEST(OdometryJacobians, MatchFiniteDifferences) {
  const Pose2 p(0.4, -0.2, deg(33));
  const WheelDisplacement u{0.031, 0.047};
  const double h = 1e-7;
  const Matrix3 Fp = odometry_jacobian_pose(p, u, kB);
  const double base[3] = {p.x, p.y, p.theta};
  for (int j = 0; j < 3; ++j) {
    double plus[3] = {base[0], base[1], base[2]}, minus[3] = {base[0], base[1], base[2]};
    plus[j] += h;
    minus[j] -= h;
    const Pose2 a = odometry_step(Pose2(plus[0], plus[1], plus[2]), u, kB);
    const Pose2 b = odometry_step(Pose2(minus[0], minus[1], minus[2]), u, kB);
    EXPECT_NEAR(Fp(0, j), (a.x - b.x) / (2 * h), 1e-7);
    EXPECT_NEAR(Fp(1, j), (a.y - b.y) / (2 * h), 1e-7);
    EXPECT_NEAR(Fp(2, j), angle_diff(a.theta, b.theta) / (2 * h), 1e-7);
  }
  const Matrix32 Fu = odometry_jacobian_wheels(p, u, kB);
  const WheelDisplacement dr_plus{u.left, u.right + h}, dr_minus{u.left, u.right - h};
  const WheelDisplacement dl_plus{u.left + h, u.right}, dl_minus{u.left - h, u.right};
  const Pose2 rp = odometry_step(p, dr_plus, kB), rm = odometry_step(p, dr_minus, kB);
  const Pose2 lp = odometry_step(p, dl_plus, kB), lm = odometry_step(p, dl_minus, kB);
  EXPECT_NEAR(Fu(0, 0), (rp.x - rm.x) / (2 * h), 1e-7);
  EXPECT_NEAR(Fu(1, 0), (rp.y - rm.y) / (2 * h), 1e-7);
  EXPECT_NEAR(Fu(2, 0), (rp.theta - rm.theta) / (2 * h), 1e-7);
  EXPECT_NEAR(Fu(0, 1), (lp.x - lm.x) / (2 * h), 1e-7);
  EXPECT_NEAR(Fu(1, 1), (lp.y - lm.y) / (2 * h), 1e-7);
  EXPECT_NEAR(Fu(2, 1), (lp.theta - lm.theta) / (2 * h), 1e-7);
}

TEST(PropagateCovariance, StraightDriveGrowsHeadingVarianceAsKOverBSquared) {
  // Σ_Δ = diag(k_r|U_R|, k_l|U_L|); straight: var(θ) = (k_r U + k_l U)/B².
  const WheelNoise k{1e-4, 1e-4};
  Matrix3 sigma = Matrix3::Zero();
  sigma = propagate_covariance(sigma, Pose2(), {0.5, 0.5}, kB, k);
  EXPECT_NEAR(sigma(2, 2), 2 * 1e-4 * 0.5 / (kB * kB), 1e-15);
  EXPECT_NEAR(sigma(0, 0), 0.25 * 2 * 1e-4 * 0.5, 1e-15);  // (k_r U + k_l U)/4
  EXPECT_NEAR(sigma(0, 1), 0.0, 1e-15);
}

TEST(PropagateCovariance, MatchesMonteCarloSpreadOfAStraightRun) {
  // 100 steps of 0.1 m each with per-wheel variance k|U| — compare Σ with sampled spread.
  const WheelNoise k{2e-4, 2e-4};
  Matrix3 sigma = Matrix3::Zero();
  Pose2 nominal;
  for (int i = 0; i < 100; ++i) {
    sigma = propagate_covariance(sigma, nominal, {0.1, 0.1}, kB, k);
    nominal = odometry_step(nominal, {0.1, 0.1}, kB);
  }
  std::uint64_t state = 12345;
  auto next_normal = [&state]() {  // small LCG + Box–Muller, test-local
    auto u = [&state]() {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return (static_cast<double>(state >> 11) + 0.5) * 0x1.0p-53;
    };
    return std::sqrt(-2 * std::log(u())) * std::cos(2 * kPi * u());
  };
  const int runs = 4000;
  double sum_y2 = 0, sum_t2 = 0;
  for (int r = 0; r < runs; ++r) {
    Pose2 p;
    for (int i = 0; i < 100; ++i) {
      const double s = std::sqrt(k.k_right * 0.1);
      p = odometry_step(p, {0.1 + s * next_normal(), 0.1 + s * next_normal()}, kB);
    }
    sum_y2 += p.y * p.y;
    sum_t2 += p.theta * p.theta;
  }
  // Sampling error of a variance from 4000 runs is ≈ √(2/4000) ≈ 2.2%; allow 10%.
  EXPECT_NEAR(sum_y2 / runs, sigma(1, 1), 0.10 * sigma(1, 1));
  EXPECT_NEAR(sum_t2 / runs, sigma(2, 2), 0.10 * sigma(2, 2));
}

}  // namespace
}  // namespace locbench
