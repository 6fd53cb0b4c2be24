// The measurement model of the ML calibration on hand-computed cases.
#include "algorithms/calibration/calibration_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.h"

namespace locbench::calibration {
namespace {

CalibrationData ticks_data(double c, double wheelbase) {
  CalibrationData d;
  d.kind = OdometryInputKind::kWheelTicks;
  d.meters_per_tick_left = c;
  d.meters_per_tick_right = c;
  d.nominal = Eigen::Vector3d(1.0, 1.0, wheelbase);
  return d;
}

CalibrationSample one(double a, double b, double dt = 0.0) {
  CalibrationSample s;
  s.increments.push_back({a, b, dt});
  return s;
}

TEST(CalibrationModel, ParametersAreNamedPerInputKind) {
  EXPECT_EQ(odometry_parameter_names(OdometryInputKind::kWheelTicks)[2], "wheelbase");
  EXPECT_EQ(odometry_parameter_names(OdometryInputKind::kWheelAngles)[0], "r_L");
  EXPECT_EQ(odometry_parameter_names(OdometryInputKind::kBodyIncrements)[2], "rotation_per_distance");
  EXPECT_EQ(odometry_parameter_names(OdometryInputKind::kVelocityIntegrals)[1], "rv_scale");
  EXPECT_EQ(sensor_parameter_names()[2], "sensor_theta");
}

TEST(CalibrationModel, AQuarterCircleArcEndsOneRadiusAheadAndOneToTheLeft) {
  // Radius 2 m: length π m, turning π/2.
  const Pose2 p = arc_displacement(kPi, kPi / 2.0);
  EXPECT_NEAR(p.x, 2.0, 1e-12);
  EXPECT_NEAR(p.y, 2.0, 1e-12);
  EXPECT_NEAR(p.theta, kPi / 2.0, 1e-12);
  const Pose2 straight = arc_displacement(1.5, 0.0);
  EXPECT_EQ(straight.x, 1.5);
  EXPECT_EQ(straight.y, 0.0);
  // The series branch near zero matches the closed form.
  const Pose2 tiny = arc_displacement(1.0, 1e-5);
  EXPECT_NEAR(tiny.y, 0.5e-5, 1e-15);
}

TEST(CalibrationModel, TicksGiveEquationOneOneAndOneTwo) {
  // 1 mm per tick, B = 0.5 m. 1000 ticks each: 1 m straight. (−500, 500): Δθ = 1/0.5 = 2 rad.
  const CalibrationData d = ticks_data(1e-3, 0.5);
  const Pose2 a = predict_robot_displacement(d, one(1000, 1000), d.nominal);
  EXPECT_NEAR(a.x, 1.0, 1e-12);
  EXPECT_NEAR(a.y, 0.0, 1e-12);
  const Pose2 b = predict_robot_displacement(d, one(-500, 500), d.nominal);
  EXPECT_NEAR(b.x, 0.0, 1e-12);
  EXPECT_NEAR(b.theta, 2.0, 1e-12);
  // A right scale of 1.1 on (1000, 1000): U_R = 1.1 m, Δθ = 0.1/0.5 = 0.2 rad, ΔD = 1.05 m.
  const Pose2 c = predict_robot_displacement(d, one(1000, 1000), Eigen::Vector3d(1.0, 1.1, 0.5));
  EXPECT_NEAR(c.theta, 0.2, 1e-12);
  EXPECT_NEAR(c.x, 1.05 * std::sin(0.2) / 0.2, 1e-12);
  EXPECT_NEAR(c.y, 1.05 * (1.0 - std::cos(0.2)) / 0.2, 1e-12);
}

TEST(CalibrationModel, IncrementsComposeInOrder) {
  // 1 m straight, then a π/2 turn on the spot, then 1 m straight: ends at (1, 1), facing +y.
  CalibrationData d = ticks_data(1e-3, 1.0);
  CalibrationSample s;
  s.increments = {{1000, 1000, 0}, {-kPi / 4.0 * 1000, kPi / 4.0 * 1000, 0}, {1000, 1000, 0}};
  const Pose2 p = predict_robot_displacement(d, s, d.nominal);
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 1.0, 1e-12);
  EXPECT_NEAR(p.theta, kPi / 2.0, 1e-12);
}

TEST(CalibrationModel, ASensorSeesTheRobotMotionConjugatedByItsMount) {
  // Robot turns π/2 on the spot; a sensor 1 m ahead of it moves to (−1, 1) in its own start
  // frame: ℓ⁻¹ ∘ o ∘ ℓ with ℓ = (1, 0, 0).
  CalibrationData d;
  d.kind = OdometryInputKind::kBodyIncrements;
  d.sensor_reference = true;
  ModelParameters p;
  p.odometry = Eigen::Vector3d(1.0, 1.0, 0.0);
  p.sensor = Pose2(1.0, 0.0, 0.0);
  const Pose2 s = predict_reference(d, one(0.0, kPi / 2.0), p);
  EXPECT_NEAR(s.x, -1.0, 1e-12);
  EXPECT_NEAR(s.y, 1.0, 1e-12);
  EXPECT_NEAR(s.theta, kPi / 2.0, 1e-12);
}

TEST(CalibrationModel, BodyAndVelocityKindsScaleAndBiasTheirIncrements) {
  CalibrationData body;
  body.kind = OdometryInputKind::kBodyIncrements;
  // d' = 1.1·2, θ' = 0.9·0.5 + 0.01·2.
  const ArcIncrement a = arc_of(body, {2.0, 0.5, 1.0}, Eigen::Vector3d(1.1, 0.9, 0.01));
  EXPECT_NEAR(a.distance, 2.2, 1e-15);
  EXPECT_NEAR(a.rotation, 0.47, 1e-15);
  CalibrationData vel;
  vel.kind = OdometryInputKind::kVelocityIntegrals;
  // θ' = 0.9·0.5 + 0.01 rad/s · 3 s.
  const ArcIncrement v = arc_of(vel, {2.0, 0.5, 3.0}, Eigen::Vector3d(1.1, 0.9, 0.01));
  EXPECT_NEAR(v.rotation, 0.48, 1e-15);
}

TEST(CalibrationModel, ArcIncrementInvertsAnArcAndSignsBackwardMotion) {
  for (double th : {0.0, 1e-7, 0.3, -1.2, 2.5}) {
    for (double d : {0.7, -0.4}) {
      const OdometryIncrement inc = arc_increment(arc_displacement(d, th), 0.1);
      EXPECT_NEAR(inc.first, d, 1e-12) << d << " " << th;
      EXPECT_NEAR(inc.second, th, 1e-12);
      EXPECT_EQ(inc.dt, 0.1);
    }
  }
  EXPECT_EQ(arc_increment(Pose2(0, 0, 0.5)).first, 0.0);
}

TEST(CalibrationModel, WheelNoiseOfAStraightStepPropagatesToTheHandComputedCovariance) {
  // U_L = U_R = 1 m, B = 0.5 m, per unit k²: var(U) = 1 m each.
  // var(ΔD) = (1 + 1)/4 = 0.5; var(Δθ) = (1 + 1)/0.25 = 8; cov(ΔD, Δθ) = (1 − 1)/(2·0.5) = 0.
  // At Δθ = 0: ∂x/∂ΔD = 1, ∂y/∂Δθ = ΔD/2 = 0.5, ∂θ/∂Δθ = 1 → var(x) = 0.5, var(y) = 2,
  // cov(y, θ) = 4, var(θ) = 8.
  const CalibrationData d = ticks_data(1e-3, 0.5);
  const NoiseShape n = odometry_noise_shape(d, one(1000, 1000), nominal_parameters(d), /*virtual_track=*/1.0);
  EXPECT_NEAR(n.per_k2(0, 0), 0.5, 1e-12);
  EXPECT_NEAR(n.per_k2(1, 1), 2.0, 1e-12);
  EXPECT_NEAR(n.per_k2(1, 2), 4.0, 1e-12);
  EXPECT_NEAR(n.per_k2(2, 2), 8.0, 1e-12);
  EXPECT_NEAR(n.per_k2(0, 2), 0.0, 1e-12);
  EXPECT_EQ(n.quantization, Eigen::Matrix3d::Zero());  // fractional ticks: no quantization
}

TEST(CalibrationModel, QuantizedTicksAddCSquaredOverSixPerWheelAndSample) {
  // One increment carries both ends' remainders: var(U) = C²/6 per wheel, C = 1 mm.
  CalibrationData d = ticks_data(1e-3, 0.5);
  d.quantized_ticks = true;
  const NoiseShape n = odometry_noise_shape(d, one(0, 0), nominal_parameters(d), 1.0);
  const double v = 1e-6 / 6.0;
  EXPECT_NEAR(n.quantization(0, 0), v / 2.0, 1e-18);         // (v + v)/4
  EXPECT_NEAR(n.quantization(2, 2), 2.0 * v / 0.25, 1e-18);  // (v + v)/B²
}

}  // namespace
}  // namespace locbench::calibration
