#include "core/pose_measurement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/compass_ekf_model.h"
#include "core/units.h"

namespace locbench {
namespace {

TEST(PoseMeasurement, LandmarkRangeAndBearingArePredictedFromThePose) {
  // Robot at (1, 2) facing 90°, landmark at (1, 5): 3 m straight ahead.
  const LandmarkRangeBearing z{3.1, 0.05, 1.0, 5.0, 0.01, 0.001};
  const LinearizedMeasurement m = linearize(z, Eigen::Vector3d(1.0, 2.0, kPi / 2));
  EXPECT_NEAR(m.predicted(0), 3.0, 1e-12);
  EXPECT_NEAR(m.predicted(1), 0.0, 1e-12);
  EXPECT_NEAR(m.residual()(0), 0.1, 1e-12);
  EXPECT_NEAR(m.residual()(1), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(m.R(0, 0), 0.01);
  EXPECT_DOUBLE_EQ(m.R(1, 1), 0.001);
  EXPECT_DOUBLE_EQ(m.R(0, 1), 0.0);
}

TEST(PoseMeasurement, LandmarkJacobianMatchesFiniteDifferences) {
  const LandmarkRangeBearing z{2.0, 0.3, 3.0, -1.0, 0.01, 0.001};
  const Eigen::Vector3d x(0.4, 0.7, 2.9);
  const LinearizedMeasurement m = linearize(z, x);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d a = x, b = x;
    a(k) += 1e-6;
    b(k) -= 1e-6;
    const LinearizedMeasurement la = linearize(z, a), lb = linearize(z, b);
    EXPECT_NEAR((la.predicted(0) - lb.predicted(0)) / 2e-6, m.H(0, k), 1e-6) << "range, state " << k;
    EXPECT_NEAR(angle_diff(la.predicted(1), lb.predicted(1)) / 2e-6, m.H(1, k), 1e-6) << "bearing, state " << k;
  }
}

TEST(PoseMeasurement, BearingResidualIsWrappedAcrossPlusMinusPi) {
  // Landmark straight behind: predicted bearing ±π; measured −179° is 1° from +180°.
  const LandmarkRangeBearing z{1.0, deg(-179.0), -1.0, 0.0, 0.01, 0.001};
  const LinearizedMeasurement m = linearize(z, Eigen::Vector3d(0.0, 0.0, 0.0));
  EXPECT_NEAR(std::abs(m.residual()(1)), deg(1.0), 1e-9);
}

TEST(PoseMeasurement, LandmarkUpdatePullsThePositionTowardTheMeasuredRange) {
  // Truth at the origin facing x, landmark 2 m ahead; the estimate is 0.3 m too far forward, so
  // the predicted range is 1.7 m against a measured 2.0 m: the update moves x back.
  Vector3 x(0.3, 0.0, 0.0);
  Matrix3 p = Matrix3::Identity() * 0.04;
  const MeasurementUpdate u = ekf_update(x, p, LandmarkRangeBearing{2.0, 0.0, 2.0, 0.0, 1e-4, 1e-4});
  EXPECT_FALSE(u.gated);
  EXPECT_NEAR(x(0), 0.3 - 0.3 * 0.04 / (0.04 + 1e-4), 1e-9);
  EXPECT_LT(p(0, 0), 1e-3);
}

TEST(PoseMeasurement, AnOutlierBeyondTheGateChangesNothing) {
  Vector3 x(0.0, 0.0, 0.0);
  Matrix3 p = Matrix3::Identity() * 1e-4;
  const Vector3 x0 = x;
  const MeasurementUpdate u = ekf_update(x, p, LandmarkRangeBearing{3.0, 0.0, 2.0, 0.0, 1e-4, 1e-4}, 13.8);
  EXPECT_TRUE(u.gated);
  EXPECT_GT(u.nis, 1000.0);
  EXPECT_EQ(x, x0);
  EXPECT_DOUBLE_EQ(p(0, 0), 1e-4);
}

}  // namespace
}  // namespace locbench
