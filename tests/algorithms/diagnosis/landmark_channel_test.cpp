// The landmark channel: hide an effect in a simulated range-bearing log, require the channel to
// name it with the true value inside its 95% interval; find nothing in null logs at the stated
// false-alarm level; say "not testable" for logs without landmarks or a map.
#include "algorithms/diagnosis/landmark_channel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/angle.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

using sim::GeneratedLog;
using sim::HiddenEffect;

LandmarkData data_of(const Log& log) { return make_landmark_data(log.landmarks, log.landmark_map, log.truth); }

std::string channel_summary(const LandmarkChannelResult& r) {
  std::string s = test_support::causes_summary(r.causes);
  for (const auto& t : r.remaining)
    s += "\n  remaining " + t.name + ":" + t.residual + " p=" + std::to_string(t.p_value);
  return s;
}

std::vector<std::string> detected_ids(const LandmarkChannelResult& r) {
  std::vector<std::string> ids;
  for (const auto& c : r.causes) {
    if (c.detected) ids.push_back(c.id);
  }
  return ids;
}

TEST(LandmarkChannel, ResidualsAreTheObservationMinusThePredictionFromTheInterpolatedTruth) {
  Log log;
  for (int k = 0; k <= 100; ++k) log.truth.push_back({0.1 * k, Pose2(0.01 * k, 0.0, 0.0), Pose2()});  // x = 0.1·t
  log.landmark_map = {{7, 5.0, 3.0, 0.0, 0.0}};
  log.landmarks = {{2.0, 7, 5.1, 0.7}, {2.0, 3, 1.0, 0.0}};  // the second: a robot, not in the map
  const LandmarkData d = data_of(log);
  ASSERT_EQ(d.readings.size(), 1u);
  EXPECT_EQ(d.unmapped, 1u);
  const auto g = landmark_geometry(d, 0.0);
  ASSERT_TRUE(g[0].valid);
  EXPECT_NEAR(g[0].rho, std::hypot(4.8, 3.0), 1e-12);  // truth at t = 2 s: x = 0.2 m
  EXPECT_NEAR(g[0].phi, std::atan2(3.0, 4.8), 1e-12);
  LandmarkModel m;
  m.range_scale = 1.01;
  m.range_bias = 0.02;
  m.bearing_bias = 0.1;
  const auto r = landmark_residual(d, 0, g[0], m);
  EXPECT_NEAR(r.range, 5.1 - (1.01 * std::hypot(4.8, 3.0) + 0.02), 1e-12);
  EXPECT_NEAR(r.bearing, wrap_angle(0.7 - std::atan2(3.0, 4.8) - 0.1), 1e-12);
  // A time offset reads the truth earlier: logged 2 s is true 1.5 s (x = 0.15 m).
  EXPECT_NEAR(landmark_geometry(d, 0.5)[0].rho, std::hypot(4.85, 3.0), 1e-12);
  // The displaced landmark is predicted at its surveyed position + (dx, dy).
  m = LandmarkModel{};
  m.position_error_id = 7;
  m.position_error_dx = 0.2;
  EXPECT_NEAR(landmark_residual(d, 0, g[0], m).rho, std::hypot(5.0, 3.0), 1e-12);
}

struct LandmarkCase {
  std::string id;
  double magnitude;
  std::string parameter;  // the catalog parameter whose interval must cover the truth
};

class LandmarkHiddenEffect : public ::testing::TestWithParam<LandmarkCase> {};

TEST_P(LandmarkHiddenEffect, IsNamedWithTheTrueValueInsideItsInterval) {
  const LandmarkCase& c = GetParam();
  const GeneratedLog g = sim::generate_landmark_log({{c.id, c.magnitude}}, 7);
  const LandmarkChannelResult r = diagnose_landmarks(data_of(g.log), DiagnosisOptions{});
  ASSERT_TRUE(r.testable);
  const auto ids = detected_ids(r);
  EXPECT_NE(std::find(ids.begin(), ids.end(), c.id), ids.end()) << channel_summary(r);
  const auto cause = std::find_if(r.causes.begin(), r.causes.end(), [&](const Cause& x) { return x.id == c.id; });
  ASSERT_NE(cause, r.causes.end());
  const double truth = g.truth.at(c.id + "." + c.parameter);
  const auto p = std::find_if(cause->parameters.begin(), cause->parameters.end(),
                              [&](const Estimate& e) { return e.name == c.parameter; });
  ASSERT_NE(p, cause->parameters.end()) << channel_summary(r);
  EXPECT_TRUE(truth >= p->lo && truth <= p->hi) << c.parameter << ": true " << truth << ", estimate " << p->value
                                                << " [" << p->lo << ", " << p->hi << "]" << channel_summary(r);
  ASSERT_FALSE(cause->gains.empty());
  EXPECT_GT(cause->gains.front().relative(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(LandmarkChannel, LandmarkHiddenEffect,
                         ::testing::Values(LandmarkCase{"landmark_range_scale", 0.03, "scale"},
                                           LandmarkCase{"landmark_range_bias", 0.04, "bias_m"},
                                           LandmarkCase{"landmark_range_off_axis_scale", -0.3, "per_rad2"},
                                           LandmarkCase{"landmark_bearing_bias", 0.02, "bias_rad"},
                                           LandmarkCase{"landmark_time_offset", 0.1, "offset_s"},
                                           LandmarkCase{"landmark_range_dependent_noise", 0.02, "slope"},
                                           LandmarkCase{"landmark_turn_dependent_bearing_noise", 0.02, "slope"},
                                           LandmarkCase{"landmark_heavy_tails", 3.0, "dof"},
                                           LandmarkCase{"landmark_position_error", 0.3, "dx_m"}),
                         [](const auto& test) { return test.param.id; });

}  // namespace
}  // namespace locbench::diagnosis

namespace locbench::diagnosis {
namespace {

// 150 null logs of 120 s (~300 observations each): at most 3 with any landmark cause detected
// (α = 0.01 per log; P(≥ 4 of 150 | p = 0.01) ≈ 0.07 — diagnosis/false_alarms measures more).
TEST(LandmarkChannel, NullLogsDetectNoLandmarkCauseAtTheStatedFalseAlarmLevel) {
  sim::LandmarkLogOptions o;
  o.duration = 120.0;
  o.odometry = false;
  int alarms = 0;
  std::string which;
  for (std::uint64_t seed = 1; seed <= 150; ++seed) {
    const GeneratedLog g = sim::generate_landmark_log({}, seed, o);
    const LandmarkChannelResult r = diagnose_landmarks(data_of(g.log), DiagnosisOptions{});
    ASSERT_TRUE(r.testable) << seed;
    const auto ids = detected_ids(r);
    if (!ids.empty()) {
      ++alarms;
      which += " seed " + std::to_string(seed) + ": " + ids.front();
    }
  }
  std::printf("null landmark logs: %d of 150 with a landmark cause detected%s\n", alarms, which.c_str());
  EXPECT_LE(alarms, 3) << which;
}

TEST(LandmarkChannel, FewerThanFortyMappedObservationsAreNotTestable) {
  sim::LandmarkLogOptions o;
  o.duration = 10.0;
  const GeneratedLog g = sim::generate_landmark_log({}, 3, o);
  const LandmarkChannelResult r = diagnose_landmarks(data_of(g.log), DiagnosisOptions{});
  EXPECT_FALSE(r.testable);
  EXPECT_TRUE(r.causes.empty());
  EXPECT_TRUE(diagnose_landmarks(LandmarkData{}, DiagnosisOptions{}).causes.empty());
}

}  // namespace
}  // namespace locbench::diagnosis
