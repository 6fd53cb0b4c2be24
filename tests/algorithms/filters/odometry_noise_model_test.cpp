#include "algorithms/filters/odometry_noise_model.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "algorithms/filters/quantization_noise.h"
#include "core/errors.h"

namespace locbench::filters {
namespace {

TEST(OdometryNoiseModel, DefaultsAreThePublishedSettingsInSi) {
  const OdometryNoiseOptions o;
  EXPECT_DOUBLE_EQ(o.k_left, 0.005);  // √m (§4.5)
  EXPECT_DOUBLE_EQ(o.k_right, 0.005);
  EXPECT_DOUBLE_EQ(o.sigma_left, 0.005);  // 5.00 mm (§4.4)
  EXPECT_DOUBLE_EQ(o.sigma_right, 0.005);
  EXPECT_EQ(o.form, OdometryNoiseForm::kThesis);
}

TEST(OdometryNoiseModel, HandComputedCase) {
  // k = 0.005 √m, σ = 5 mm, U_L = 60 mm, U_R = 65 mm, B = 0.2 m, θ(k−1) = 30°:
  // k²|U_L| = 1.5e-6, k²|U_R| = 1.625e-6, σ_l² + σ_r² = 5e-5 → sum 5.3125e-5 m².
  const OdometryNoiseOptions o;
  const WheelDisplacement u{0.060, 0.065};
  const IncrementNoise n = increment_noise(o, u, 0.2);
  EXPECT_NEAR(n.distance, 1.328125e-5, 1e-18);  // eq. 4.36: sum/4
  EXPECT_NEAR(n.rotation, 1.328125e-3, 1e-15);  // eq. 4.37: sum/B²
  // Δθ = 0.025 rad, θ + Δθ/2 = π/6 + 0.0125 (eq. 4.43).
  const Matrix3 q = adaptive_process_noise(o, deg(30.0), u, 0.2);
  EXPECT_NEAR(q(0, 0), 9.816141183673165e-06, 1e-18);
  EXPECT_NEAR(q(1, 1), 3.465108816326833e-06, 1e-18);
  EXPECT_NEAR(q(2, 2), 1.328125e-3, 1e-15);
  EXPECT_DOUBLE_EQ(q(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(q(0, 2), 0.0);
  EXPECT_DOUBLE_EQ(q(1, 2), 0.0);
}

TEST(OdometryNoiseModel, StandingStillLeavesOnlyTheQuantizationTerm) {
  OdometryNoiseOptions o;
  o.sigma_left = 0.003;
  o.sigma_right = 0.004;
  const IncrementNoise n = increment_noise(o, {0.0, 0.0}, 0.2);
  EXPECT_NEAR(n.distance, (9e-6 + 16e-6) / 4.0, 1e-18);
  EXPECT_NEAR(n.rotation, (9e-6 + 16e-6) / 0.04, 1e-15);
  // Backward travel counts by its magnitude.
  EXPECT_DOUBLE_EQ(increment_noise(o, {-0.05, -0.06}, 0.2).distance, increment_noise(o, {0.05, 0.06}, 0.2).distance);
}

TEST(OdometryNoiseModel, SigmaFromTheQuantizationModel) {
  // The Gaussian stand-in for a 12.64 mm tick (see quantization_noise.h) plugs in directly.
  OdometryNoiseOptions o;
  o.sigma_left = mm(l2_optimal_sigma(12.64));
  o.sigma_right = mm(l2_optimal_sigma(12.70));
  const IncrementNoise n = increment_noise(o, {0.0, 0.0}, 0.19793);
  EXPECT_NEAR(n.distance, (std::pow(0.0055185, 2) + std::pow(0.0055447, 2)) / 4.0, 1e-9);
}

TEST(OdometryNoiseModel, JacobianFormKeepsTheLateralAndCrossTerms) {
  OdometryNoiseOptions o;
  o.form = OdometryNoiseForm::kJacobian;
  const WheelDisplacement u{0.060, 0.065};
  const Matrix3 q = adaptive_process_noise(o, 0.0, u, 0.2);
  const WheelNoiseVariance w = wheel_noise_variance(o, u);
  // θθ entry is the same as eq. 4.37; the matrix is F_u diag(var_R, var_L) F_uᵀ, rank 2.
  EXPECT_NEAR(q(2, 2), (w.left + w.right) / 0.04, 1e-15);
  const Matrix32 fu = odometry_jacobian_wheels(Pose2(), u, 0.2);
  const Matrix3 expected = fu * Eigen::Vector2d(w.right, w.left).asDiagonal() * fu.transpose();
  EXPECT_TRUE(q.isApprox(expected, 1e-14));
  EXPECT_GT(q(1, 1), 0.0);  // lateral term even at θ = 0
  EXPECT_NE(q(0, 2), 0.0);  // unequal wheel variances correlate w_d and w_θ
  EXPECT_NEAR(q.determinant(), 0.0, 1e-30);
  // Standing still at θ = 0, x and θ terms agree with the thesis's form.
  const Matrix3 still = adaptive_process_noise(o, 0.0, {0.0, 0.0}, 0.2);
  const Matrix3 thesis = adaptive_process_noise(OdometryNoiseOptions{}, 0.0, {0.0, 0.0}, 0.2);
  EXPECT_NEAR(still(0, 0), thesis(0, 0), 1e-18);
  EXPECT_NEAR(still(2, 2), thesis(2, 2), 1e-15);
}

TEST(OdometryNoiseModel, JsonRoundTripAndStrictness) {
  OdometryNoiseOptions o;
  o.k_left = 0.001;
  o.sigma_right = 0.002;
  o.form = OdometryNoiseForm::kJacobian;
  const nlohmann::json j = o;
  const auto back = j.get<OdometryNoiseOptions>();
  EXPECT_DOUBLE_EQ(back.k_left, 0.001);
  EXPECT_DOUBLE_EQ(back.sigma_right, 0.002);
  EXPECT_EQ(back.form, OdometryNoiseForm::kJacobian);
  EXPECT_EQ(nlohmann::json(back), j);
  // Absent keys keep defaults.
  EXPECT_DOUBLE_EQ(nlohmann::json::object().get<OdometryNoiseOptions>().k_right, 0.005);
  EXPECT_THROW((nlohmann::json{{"k_lft", 0.1}}.get<OdometryNoiseOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"k_left", "0.1"}}.get<OdometryNoiseOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"form", "diagonal"}}.get<OdometryNoiseOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json{{"sigma_left", -1.0}}.get<OdometryNoiseOptions>()), UsageError);
  EXPECT_THROW((nlohmann::json::array().get<OdometryNoiseOptions>()), UsageError);
  try {
    (void)nlohmann::json{{"bogus", 1}}.get<OdometryNoiseOptions>();
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("bogus"), std::string::npos);
  }
}

}  // namespace
}  // namespace locbench::filters
