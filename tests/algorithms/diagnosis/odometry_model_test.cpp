// The odometry model's parts checked against independent computations: the drive response
// against a fine Euler integration, the Student-t density against its normalisation and its
// normal limit, the window prediction against the scales it is given.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {
namespace {

// Velocity odometry: `n` steps of 0.1 s, the logged speed `v(i)` and turn rate 0.
MotionData straight_steps(std::size_t n, double (*v)(std::size_t)) {
  MotionData d;
  d.odometry = OdometryKind::kPose;
  d.reference = ReferenceKind::kRelations;
  for (std::size_t i = 0; i < n; ++i) {
    const double t0 = 0.1 * static_cast<double>(i);
    d.steps.push_back({t0, t0 + 0.1, v(i) * 0.1, 0.0});
  }
  return d;
}

TEST(OdometryModel, TheDriveResponseMovesAsAFineEulerIntegrationOfTheFirstOrderLag) {
  // The logged speed jumps from 0 to 0.5 m/s at step 20; τ = 0.3 s.
  const MotionData d = straight_steps(40, [](std::size_t i) { return i < 20 ? 0.0 : 0.5; });
  MotionWindow w;
  w.first = 20;
  w.last = 30;  // the first second after the jump
  OdometryModel m;
  m.drive_tau = 0.3;
  const Pose2 p = predict_window(d, w, m);
  double u = 0.0, x = 0.0;
  for (int k = 0; k < 100000; ++k) {
    u += (0.5 - u) * 1e-5 / 0.3;
    x += u * 1e-5;
  }
  EXPECT_NEAR(p.x, x, 1e-5);  // Euler at 10 µs is good to ~5 µm; 0.5·(1 − 0.3·(1 − e^(−1/0.3))) = 0.3554 m
  EXPECT_NEAR(p.x, 0.5 * (1.0 - 0.3 * (1.0 - std::exp(-1.0 / 0.3))), 1e-9);
}

TEST(OdometryModel, ScalesActOnTheLoggedMotionAndTheSpeedSlopeOnItsSpeed) {
  const MotionData d = straight_steps(10, [](std::size_t) { return 0.4; });
  MotionWindow w;
  w.first = 0;
  w.last = 10;
  OdometryModel m;
  m.velocity_scale = 0.95;
  EXPECT_NEAR(predict_window(d, w, m).x, 0.95 * 0.4, 1e-12);
  m.speed_slope = -0.1;  // (0.95 − 0.1·0.4)·0.4
  EXPECT_NEAR(predict_window(d, w, m).x, (0.95 - 0.04) * 0.4, 1e-12);
}

TEST(OdometryModel, TheStudentTDensityIsNormalisedAndTendsToTheNormal) {
  for (double dof : {1.5, 3.0, 10.0}) {
    double mass = 0.0;
    for (double r = -2000.0; r <= 2000.0; r += 0.01) mass += std::exp(component_log_density(r, 4.0, dof)) * 0.01;
    EXPECT_NEAR(mass, 1.0, dof < 2.0 ? 2e-2 : 1e-3) << dof;
  }
  EXPECT_NEAR(component_log_density(1.3, 2.0, 1e7), component_log_density(1.3, 2.0, 0.0), 1e-6);
  // Heavier tails: at 5 scale units the t with 3 dof is far more likely than the normal.
  EXPECT_GT(component_log_density(5.0, 1.0, 3.0), component_log_density(5.0, 1.0, 0.0) + 5.0);
}

}  // namespace
}  // namespace locbench::diagnosis
