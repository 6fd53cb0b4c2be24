// The odometry channel's residual battery on residuals with one planted structure each: the
// structure's test is significant, the clean residuals' is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "algorithms/diagnosis/odometry_battery.h"
#include "core/rng.h"

namespace locbench::diagnosis {
namespace {

// 400 windows of standardized normal residuals with covariates that vary.
OdoResiduals clean(std::uint64_t seed) {
  Rng rng(seed), sideways(seed + 1000);  // the lateral residuals from a stream of their own
  OdoResiduals o;
  for (int k = 0; k < 400; ++k) {
    o.along.push_back(rng.normal());
    o.lateral.push_back(sideways.normal());
    o.heading.push_back(rng.normal());
    o.distance.push_back(rng.uniform(0.0, 0.5));
    o.turn.push_back(rng.uniform(-0.5, 0.5));
    o.speed.push_back(rng.uniform(0.0, 0.5));
    o.travel.push_back(rng.uniform(0.0, 1.0));
    const double h = rng.uniform(-3.0, 3.0);
    o.cos_h.push_back(std::cos(h));
    o.sin_h.push_back(std::sin(h));
    o.x.push_back(rng.uniform(0.0, 5.0));
    o.y.push_back(rng.uniform(0.0, 5.0));
    o.dturn.push_back(rng.uniform(-0.2, 0.2));
  }
  return o;
}

double p_value(const std::vector<ResidualTest>& tests, const std::string& name, const std::string& residual) {
  const auto it = std::find_if(tests.begin(), tests.end(),
                               [&](const ResidualTest& t) { return t.name == name && t.residual == residual; });
  if (it == tests.end()) throw std::runtime_error("no test " + name + " of " + residual);
  return it->p_value;
}

MotionData positions() {
  MotionData d;
  d.odometry = OdometryKind::kPose;
  d.reference = ReferenceKind::kTruePose;
  return d;
}

TEST(OdometryBattery, CleanResidualsPassAndAnAlongTrackLossGrowingWithSpeedIsFound) {
  OdoResiduals o = clean(5);
  EXPECT_GT(p_value(odometry_battery(positions(), o), "speed_dependence", "along_track"), 1e-3);
  for (std::size_t k = 0; k < o.along.size(); ++k) o.along[k] -= 2.0 * o.speed[k];  // 0 to −1σ
  const auto tests = odometry_battery(positions(), o);
  EXPECT_LT(p_value(tests, "speed_dependence", "along_track"), 1e-6);
  EXPECT_LT(p_value(tests, "bias", "along_track"), 1e-6);
  EXPECT_GT(p_value(tests, "bias", "heading"), 1e-3);
}

TEST(OdometryBattery, ASidewaysDriftGrowingWithDistanceIsFoundInTheLateralResiduals) {
  // A reference frame turned by δ against the direction of travel: the lateral residual is −δ·d.
  OdoResiduals o = clean(7);
  EXPECT_GT(p_value(odometry_battery(positions(), o), "drift_with_distance", "lateral"), 1e-3);
  for (std::size_t k = 0; k < o.lateral.size(); ++k) o.lateral[k] -= 3.0 * o.distance[k];  // 0 to −1.5σ
  const auto tests = odometry_battery(positions(), o);
  EXPECT_LT(p_value(tests, "drift_with_distance", "lateral"), 1e-6);
  EXPECT_GT(p_value(tests, "drift_with_distance", "along_track"), 1e-3);
}

TEST(OdometryBattery, AHeadingOnlyReferenceHasNoAlongTrackOrLateralTests) {
  MotionData d = positions();
  d.reference = ReferenceKind::kCompass;
  for (const auto& t : odometry_battery(d, clean(6))) {
    EXPECT_NE(t.residual, "along_track") << t.name;
    EXPECT_NE(t.residual, "lateral") << t.name;
  }
}

}  // namespace
}  // namespace locbench::diagnosis
