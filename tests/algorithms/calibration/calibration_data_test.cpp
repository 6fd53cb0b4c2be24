// Builders of calibration samples from logs and calibration files.
#include "algorithms/calibration/calibration_data.h"

#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/calibration/calibration_model.h"
#include "core/errors.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"

namespace locbench::calibration {
namespace {

// Pose after driving an arc of constant speed v and turn rate w for t seconds from the origin.
Pose2 on_circle(double v, double w, double t) { return arc_displacement(v * t, w * t); }

// ODOM records along a circle (0.2 m/s, 0.1 rad/s) at 10 Hz for 20 s, and the same path as
// ground truth at 100 Hz.
Log circle_log() {
  Log log;
  log.source = "circle";
  for (int k = 0; k <= 200; ++k) {
    const double t = 0.1 * k;
    log.odometry.push_back({t, on_circle(0.2, 0.1, t), 0.2, 0.1});
  }
  for (int k = 0; k <= 2000; ++k) {
    const double t = 0.01 * k;
    log.truth.push_back({t, on_circle(0.2, 0.1, t), Pose2()});
  }
  return log;
}

double pose_gap(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y) + std::abs(angle_diff(a.theta, b.theta));
}

TEST(CalibrationData, EncoderSamplesOfAnIdealRobotMatchTheirGroundTruth) {
  const auto sim = sim::simulate(sim::preset("ideal"), 1);  // 10 m straight, exact geometry
  SampleIntervalOptions o;
  o.max_distance = 0.5;
  const CalibrationData d = calibration_data_from_encoders(sim.log, o);
  EXPECT_EQ(d.kind, OdometryInputKind::kWheelTicks);
  EXPECT_TRUE(d.quantized_ticks);
  EXPECT_FALSE(d.sensor_reference);
  EXPECT_EQ(d.nominal(0), 1.0);
  EXPECT_NEAR(d.nominal(2), 1.2 / kPi, 1e-15);
  EXPECT_NEAR(d.meters_per_tick_left, 1e-4, 1e-15);
  // 10 m in samples of about 0.5 m (the last one at the end of the motion may be shorter).
  EXPECT_GE(d.samples.size(), 20u);
  EXPECT_LE(d.samples.size(), 21u);
  for (const CalibrationSample& s : d.samples) {
    EXPECT_LT(s.t_start, s.t_end);
    // Exact geometry: the nominal odometry reproduces the truth up to a tick (0.1 mm).
    EXPECT_LT(pose_gap(predict_reference(d, s, nominal_parameters(d)), s.reference), 2e-4);
    EXPECT_LE(std::abs(s.reference.x), 0.5 + 0.025 + 1e-9);  // 0.5 m + one 10 Hz step
  }
}

TEST(CalibrationData, EncoderSamplesNeedGroundTruthAndANominalModel) {
  auto sim = sim::simulate(sim::preset("ideal"), 1);
  Log no_truth = sim.log;
  no_truth.truth.clear();
  EXPECT_THROW(calibration_data_from_encoders(no_truth), InputError);
  Log no_model = sim.log;
  no_model.params.clear();
  EXPECT_THROW(calibration_data_from_encoders(no_model), InputError);
  EXPECT_NO_THROW(calibration_data_from_encoders(no_model, {}, NominalModel{1e-4, 1e-4, 0.4}));
}

TEST(CalibrationData, ASensorMountTurnsTheReferenceIntoTheSensorsDisplacement) {
  const auto sim = sim::simulate(sim::preset("ideal"), 1);
  const Pose2 mount(0.1, 0.05, 0.3);
  const CalibrationData d = calibration_data_from_encoders(sim.log, {}, std::nullopt, mount);
  ASSERT_TRUE(d.sensor_reference);
  ModelParameters p = nominal_parameters(d);
  p.sensor = mount;
  for (const CalibrationSample& s : d.samples) {
    EXPECT_LT(pose_gap(predict_reference(d, s, p), s.reference), 2e-4);
  }
}

TEST(CalibrationData, VelocitySamplesIntegrateTheLoggedVelocitiesAlongArcs) {
  const Log log = circle_log();
  SampleIntervalOptions o;
  o.max_duration = 2.0;
  const CalibrationData d = calibration_data_from_velocities(log, o);
  EXPECT_EQ(d.kind, OdometryInputKind::kVelocityIntegrals);
  EXPECT_EQ(d.samples.size(), 10u);  // 20 s of odometry in 2 s samples
  ASSERT_EQ(d.samples[0].increments.size(), 20u);
  EXPECT_NEAR(d.samples[0].increments[0].first, 0.02, 1e-15);
  EXPECT_NEAR(d.samples[0].increments[0].second, 0.01, 1e-15);
  EXPECT_NEAR(d.samples[0].increments[0].dt, 0.1, 1e-15);
  for (const CalibrationSample& s : d.samples) {
    EXPECT_LT(pose_gap(predict_reference(d, s, nominal_parameters(d)), s.reference), 1e-9);
  }
}

TEST(CalibrationData, VelocitySamplesSkipGroundTruthGapsAndShiftByTheTimeOffset) {
  Log log = circle_log();
  // Remove the ground truth between 5 s and 6 s: the sample covering it disappears.
  std::erase_if(log.truth, [](const TruePose& p) { return p.t > 5.0 && p.t < 6.0; });
  SampleIntervalOptions o;
  o.max_duration = 2.0;
  const CalibrationData d = calibration_data_from_velocities(log, o);
  EXPECT_EQ(d.samples.size(), 9u);
  for (const CalibrationSample& s : d.samples) EXPECT_FALSE(s.t_start < 6.0 && s.t_end > 5.0);
  o.odometry_time_offset = 0.5;
  const CalibrationData shifted = calibration_data_from_velocities(circle_log(), o);
  EXPECT_NEAR(shifted.samples[0].t_start, 0.5, 1e-12);
}

TEST(CalibrationData, RelationSamplesReproduceTheOdometryBetweenTheRelationTimes) {
  Log log = circle_log();
  log.relations = {{12.0, 13.5, Pose2(0.3, 0.0, 0.0)},  // at ODOM records
                   {2.0, 2.3, Pose2(0.06, 0.0, 0.0)},
                   {5.05, 7.43, Pose2()},               // between records
                   {9.0, 8.0, Pose2(-0.2, 0.0, -0.1)},  // reversed
                   {19.0, 25.0, Pose2()}};              // outside the odometry
  const CalibrationData d = calibration_data_from_relations(log);
  EXPECT_EQ(d.kind, OdometryInputKind::kBodyIncrements);
  ASSERT_EQ(d.samples.size(), 4u);
  EXPECT_EQ(d.samples[0].t_start, 2.0);  // in order of t1
  EXPECT_EQ(d.samples[1].t_start, 5.05);
  EXPECT_EQ(d.samples[2].t_start, 8.0);
  EXPECT_EQ(d.samples[3].t_start, 12.0);
  EXPECT_EQ(d.samples[3].increments.size(), 15u);
  const ModelParameters p = nominal_parameters(d);
  auto odom = [](double t) { return on_circle(0.2, 0.1, t); };
  EXPECT_LT(pose_gap(predict_reference(d, d.samples[3], p), between(odom(12.0), odom(13.5))), 1e-12);
  EXPECT_LT(pose_gap(predict_reference(d, d.samples[1], p), between(odom(5.05), odom(7.43))), 1e-3);
  // The reversed relation is turned around: from 8 s to 9 s.
  EXPECT_NEAR(d.samples[2].reference.x, Pose2(-0.2, 0.0, -0.1).inverse().x, 1e-15);
  RelationSampleOptions short_only;
  short_only.max_duration = 1.6;
  EXPECT_EQ(calibration_data_from_relations(log, short_only).samples.size(), 3u);
  log.relations.clear();
  EXPECT_THROW(calibration_data_from_relations(log), InputError);
}

TEST(CalibrationData, FileRecordsBecomeOneSamplePerRow) {
  const std::vector<WheelSpeedTuple> tuples = {{0.8, 0.5, -0.5, Pose2(0.001, 0.0, -0.18)}};
  const CalibrationData c = calibration_data_from_wheel_speed_tuples(tuples);
  EXPECT_EQ(c.kind, OdometryInputKind::kWheelAngles);
  EXPECT_TRUE(c.sensor_reference);
  EXPECT_EQ(c.nominal, Eigen::Vector3d(0.021, 0.021, 0.09));
  ASSERT_EQ(c.samples.size(), 1u);
  EXPECT_DOUBLE_EQ(c.samples[0].increments[0].first, 0.4);  // T·phi_l [rad]
  EXPECT_DOUBLE_EQ(c.samples[0].increments[0].second, -0.4);
  EXPECT_EQ(c.samples[0].reference.theta, -0.18);

  const std::vector<RelativeMotionPair> pairs = {{arc_displacement(0.3, 0.2), Pose2(0.3, 0, 0.2)}};
  const CalibrationData m = calibration_data_from_motion_pairs(pairs);
  EXPECT_EQ(m.kind, OdometryInputKind::kBodyIncrements);
  EXPECT_NEAR(m.samples[0].increments[0].first, 0.3, 1e-12);
  EXPECT_NEAR(m.samples[0].increments[0].second, 0.2, 1e-12);

  const std::vector<TickMotion> rows = {{-0.02, 0.02, Pose2(0.015, 0, 0)}};
  const CalibrationData t = calibration_data_from_tick_motions(rows);
  EXPECT_EQ(t.kind, OdometryInputKind::kWheelTicks);
  EXPECT_FALSE(t.quantized_ticks);
  EXPECT_EQ(t.meters_per_tick_left, -1.0);
  EXPECT_EQ(t.nominal(2), 1.0);
  // Nominal: U_L = −1·(−0.02), U_R = 0.02 → 2 cm straight.
  EXPECT_NEAR(predict_reference(t, t.samples[0], nominal_parameters(t)).x, 0.02, 1e-15);
}

TEST(CalibrationData, SubsetKeepsTheKindAndNominalValues) {
  const std::vector<WheelSpeedTuple> tuples(5, {0.8, 0.5, -0.5, Pose2()});
  const CalibrationData all = calibration_data_from_wheel_speed_tuples(tuples);
  const CalibrationData part = subset(all, 1, 3);
  EXPECT_EQ(part.samples.size(), 2u);
  EXPECT_EQ(part.kind, all.kind);
  EXPECT_EQ(part.nominal, all.nominal);
  EXPECT_EQ(subset(all, 4, 99).samples.size(), 1u);
}

}  // namespace
}  // namespace locbench::calibration
