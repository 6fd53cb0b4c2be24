// Hide an effect in a simulated log, require `diagnose` to find it: name it, put the true
// parameter inside its 95% interval (or within the stated tolerance) and report a positive
// held-out gain — and find nothing in logs with nothing hidden. The diagnosis reads only the
// log; the generator's truth is compared with the report here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/units.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "tests/algorithms/diagnosis/diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

using sim::GeneratedLog;
using sim::HiddenEffect;
using test_support::detected;
using test_support::find_cause;
using test_support::summary;

// The true value is in the interval, or within `tolerance` (relative to the value's size) of it.
void expect_covers(const Diagnosis& d, const GeneratedLog& g, const std::string& key, double tolerance) {
  const auto dot = key.find('.');
  const Cause* c = find_cause(d, key.substr(0, dot));
  ASSERT_NE(c, nullptr) << key;
  const auto it = std::find_if(c->parameters.begin(), c->parameters.end(),
                               [&](const Estimate& e) { return e.name == key.substr(dot + 1); });
  ASSERT_NE(it, c->parameters.end()) << key;
  const double truth = g.truth.at(key);
  const double slack = tolerance * std::abs(truth);
  EXPECT_TRUE(truth >= it->lo - slack && truth <= it->hi + slack)
      << key << ": true " << truth << ", estimate " << it->value << " [" << it->lo << ", " << it->hi << "]\n"
      << summary(d);
}

void expect_positive_gain(const Diagnosis& d, const std::string& id) {
  const Cause* c = find_cause(d, id);
  ASSERT_NE(c, nullptr);
  ASSERT_FALSE(c->gains.empty()) << id;
  EXPECT_GT(c->gains.front().relative(), 0.0)
      << id << " " << c->gains.front().metric << ": " << c->gains.front().before << " → " << c->gains.front().after;
}

Diagnosis run(const std::vector<HiddenEffect>& effects, std::uint64_t seed, sim::GeneratorOptions o = {}) {
  return diagnose_log(sim::generate_log(effects, seed, o).log);
}

TEST(DiagnoseHiddenEffects, NullLogsDetectNothing) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const Diagnosis d = run({}, seed);
    EXPECT_TRUE(d.detected.empty()) << "seed " << seed << "\n" << summary(d);
    EXPECT_TRUE(d.unexplained.empty()) << "seed " << seed << "\n" << summary(d);
    EXPECT_NE(d.verdict.find("No significant discrepancy"), std::string::npos) << d.verdict;
  }
}

struct Case {
  std::string id;
  double magnitude;
  std::string key;   // parameter compared with the truth
  double tolerance;  // relative slack beyond the interval
  bool velocity = false;
  int waypoints = 16;
};

class OneEffect : public ::testing::TestWithParam<Case> {};

TEST_P(OneEffect, IsNamedWithTheTrueParameterAndAHeldOutGain) {
  const Case& c = GetParam();
  sim::GeneratorOptions o;
  o.velocity_odometry = c.velocity;
  o.waypoints = c.waypoints;
  const GeneratedLog g = sim::generate_log({{c.id, c.magnitude}}, 11, o);
  const Diagnosis d = diagnose_log(g.log);
  ASSERT_TRUE(detected(d, c.id)) << summary(d);
  EXPECT_EQ(d.detected.front(), c.id) << summary(d);
  expect_covers(d, g, c.key, c.tolerance);
  expect_positive_gain(d, c.id);
}

INSTANTIATE_TEST_SUITE_P(
    Catalog, OneEffect,
    ::testing::Values(Case{"wheel_diameter_ratio", 0.004, "wheel_diameter_ratio.E_d", 0.0},
                      Case{"wheelbase_scale", 0.01, "wheelbase_scale.E_b", 0.0},
                      Case{"mean_diameter_scale", 0.01, "mean_diameter_scale.E_o", 0.0},
                      Case{"odometry_noise_growth", 1e-4, "odometry_noise_growth.k2_m", 0.0},
                      Case{"wheel_slip", 0.2, "wheel_slip.rate_per_m", 0.3},
                      Case{"sensor_time_offset", 0.05, "sensor_time_offset.offset_s", 0.02},
                      Case{"compass_bias", deg(2.0), "compass_bias.bias_rad", 0.0},
                      Case{"compass_quantization", deg(2.0), "compass_quantization.step_rad", 0.0, false, 60},
                      Case{"compass_disturbance", deg(10.0), "compass_disturbance.max_bias_rad", 0.25},
                      Case{"velocity_scale", 0.02, "velocity_scale.scale", 0.0, true},
                      Case{"turn_rate_scale", 0.02, "turn_rate_scale.scale", 0.0, true},
                      Case{"turn_rate_bias", 0.01, "turn_rate_bias.bias_rad_s", 0.0, true}),
    [](const auto& p) { return p.param.id; });

}  // namespace
}  // namespace locbench::diagnosis

namespace locbench::diagnosis {
namespace {

// Each "cause.parameter" names a detected cause whose parameter's interval covers the truth.
void expect_named_and_covered(const Diagnosis& d, const GeneratedLog& g, std::initializer_list<std::string> keys) {
  for (const std::string& key : keys) {
    EXPECT_TRUE(detected(d, key.substr(0, key.find('.')))) << summary(d);
    expect_covers(d, g, key, 0.0);
  }
}

TEST(DiagnoseHiddenEffects, TwoEffectsAtOnceAreBothNamed) {
  const GeneratedLog g = sim::generate_log({{"wheel_diameter_ratio", 0.004}, {"compass_bias", deg(3.0)}}, 21);
  expect_named_and_covered(diagnose_log(g.log), g, {"wheel_diameter_ratio.E_d", "compass_bias.bias_rad"});
}

TEST(DiagnoseHiddenEffects, WheelbaseAndMeanDiameterTogetherAreSeparatedByGroundTruth) {
  const GeneratedLog g = sim::generate_log({{"wheelbase_scale", 0.01}, {"mean_diameter_scale", -0.01}}, 22);
  expect_named_and_covered(diagnose_log(g.log), g, {"wheelbase_scale.E_b", "mean_diameter_scale.E_o"});
}

TEST(DiagnoseHiddenEffects, EncoderQuantizationIsFoundAsALatticeInTheCounts) {
  const GeneratedLog g = sim::generate_log({{"encoder_quantization", 8}}, 23);
  const Diagnosis d = diagnose_log(g.log);
  ASSERT_TRUE(detected(d, "encoder_quantization")) << summary(d);
  expect_covers(d, g, "encoder_quantization.step_m", 1e-9);
}

}  // namespace
}  // namespace locbench::diagnosis

namespace locbench::diagnosis {
namespace {

TEST(DiagnoseReferences, OnAHeadingOnlyReferenceWheelbaseAndMeanDiameterAreOneConfoundedGroup) {
  sim::GeneratorOptions o;
  o.reference = sim::GeneratedReference::kCompass;
  const GeneratedLog g = sim::generate_log({{"wheelbase_scale", 0.02}}, 31, o);
  const Diagnosis d = diagnose_log(g.log);
  ASSERT_FALSE(d.detected.empty()) << summary(d);
  const std::string first = d.detected.front();
  EXPECT_TRUE(first == "wheelbase_scale" || first == "mean_diameter_scale") << summary(d);
  ASSERT_EQ(d.confounded.size(), 1u) << summary(d);
  const auto& ids = d.confounded.front().ids;
  EXPECT_NE(std::find(ids.begin(), ids.end(), "wheelbase_scale"), ids.end());
  EXPECT_NE(std::find(ids.begin(), ids.end(), "mean_diameter_scale"), ids.end());
  EXPECT_FALSE(find_cause(d, first)->identifiable);
  // The combination the data determine is E_b/E_o = 1.02 (or its inverse).
  const auto& p = find_cause(d, first)->parameters.front();
  const double ratio = first == "wheelbase_scale" ? 1.02 : 1.0 / 1.02;
  EXPECT_LT(p.lo, ratio) << d.confounded.front().combination;
  EXPECT_GT(p.hi, ratio) << d.confounded.front().combination;
}

TEST(DiagnoseReferences, RelationsAsTheReferenceFindAWheelDiameterRatio) {
  sim::GeneratorOptions o;
  o.reference = sim::GeneratedReference::kRelations;
  const GeneratedLog g = sim::generate_log({{"wheel_diameter_ratio", 0.005}}, 32, o);
  ASSERT_FALSE(g.log.relations.empty());
  const Diagnosis d = diagnose_log(g.log);
  ASSERT_FALSE(d.detected.empty()) << summary(d);
  EXPECT_EQ(d.detected.front(), "wheel_diameter_ratio") << summary(d);
  expect_covers(d, g, "wheel_diameter_ratio.E_d", 0.0);
}

TEST(DiagnoseReferences, NullLogsWithRelationsOrACompassDetectNothing) {
  for (auto ref : {sim::GeneratedReference::kRelations, sim::GeneratedReference::kCompass}) {
    sim::GeneratorOptions o;
    o.reference = ref;
    const Diagnosis d = diagnose_log(sim::generate_log({}, 33, o).log);
    EXPECT_TRUE(d.detected.empty()) << summary(d);
    EXPECT_TRUE(d.unexplained.empty()) << summary(d);
  }
}

}  // namespace
}  // namespace locbench::diagnosis
