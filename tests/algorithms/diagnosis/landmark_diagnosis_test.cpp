// The landmark channel inside `diagnose_log`: it runs when the log has landmark observations, a
// map and TRUEPOS, and is "not testable" otherwise; the report carries the fitted models, which
// read back strictly (a filter loads them from `diagnose --report` output).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "reports/schema_validation.h"
#include "tests/algorithms/diagnosis/diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

sim::GeneratedLog velocity_log_with_landmarks(const std::vector<sim::HiddenEffect>& effects) {
  sim::GeneratorOptions o;
  o.velocity_odometry = true;
  o.compass = false;
  sim::GeneratedLog g = sim::generate_log({}, 31, o);
  sim::add_landmark_observations(g, effects, 31);
  return g;
}

bool names_landmark_causes(const std::vector<std::string>& not_testable) {
  return std::any_of(not_testable.begin(), not_testable.end(),
                     [](const std::string& s) { return s.find("landmark_range_bias") != std::string::npos; });
}

TEST(LandmarkDiagnosis, ALogWithLandmarksAMapAndTruthGetsTheChannelAndItsModelInTheReport) {
  const sim::GeneratedLog g = velocity_log_with_landmarks({{"landmark_range_bias", 0.05}});
  const Diagnosis d = diagnose_log(g.log);
  EXPECT_TRUE(test_support::detected(d, "landmark_range_bias")) << test_support::summary(d);
  EXPECT_FALSE(names_landmark_causes(d.not_testable));
  ASSERT_TRUE(d.landmark_model.has_value());
  EXPECT_NEAR(d.landmark_model->range_bias, 0.05, 0.01);
  ASSERT_TRUE(d.odometry_model.has_value());
  EXPECT_EQ(d.odometry_kind, "velocity");

  const nlohmann::json j = to_json(d);
  EXPECT_TRUE(reports::validate_diagnosis_json(j).empty());
  const FittedModels m = read_fitted_models(j);
  ASSERT_TRUE(m.landmark && m.odometry);
  EXPECT_DOUBLE_EQ(m.landmark->range_bias, d.landmark_model->range_bias);
  EXPECT_DOUBLE_EQ(m.landmark->sigma_bearing, d.landmark_model->sigma_bearing);
  EXPECT_DOUBLE_EQ(m.odometry->sigma_theta, d.odometry_model->sigma_theta);
  EXPECT_EQ(m.odometry_kind, "velocity");
  EXPECT_DOUBLE_EQ(m.odometry_window_s, 1.0);
}

TEST(DiagnosisThreads, TheReportIsTheSameOnOneThreadAsOnMany) {
  // The channels run side by side, and the odometry channel fits each selection round's candidates
  // side by side: a log with causes in both channels, diagnosed on 1 thread and on 4, gives the
  // same report to the last bit.
  sim::GeneratorOptions o;
  o.velocity_odometry = true;
  o.compass = false;
  o.waypoints = 8;
  sim::GeneratedLog g = sim::generate_log({{"velocity_scale", 0.05}, {"turn_rate_scale", 0.05}}, 12, o);
  sim::add_landmark_observations(g, {{"landmark_range_bias", 0.05}}, 12);
  nlohmann::json one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = to_json(diagnose_log(g.log));
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
    many = to_json(diagnose_log(g.log));
  }
  one.erase("provenance");
  many.erase("provenance");
  ASSERT_GE(one.at("detected").size(), 2u) << one.at("detected").dump();
  EXPECT_EQ(one.dump(), many.dump());
}

TEST(LandmarkDiagnosis, TheOdometryModelHoldsOnlyTheDetectedOdometryCausesWithTheirFittedValues) {
  sim::GeneratorOptions o;
  o.velocity_odometry = true;
  o.compass = false;
  const Diagnosis d = diagnose_log(sim::generate_log({{"velocity_scale", 0.05}}, 12, o).log);
  ASSERT_FALSE(d.detected.empty()) << test_support::summary(d);
  ASSERT_TRUE(d.odometry_model.has_value());
  // The detected causes' parameters are the model's; every other cause's parameter is nominal
  // unless a detected cause shares it (speed_dependent_scale sets velocity_scale too).
  std::vector<double OdometryModel::*> set;
  for (const auto& c : d.causes) {
    if (c.channel != "odometry" || !c.detected) continue;
    for (const auto& p : cause_spec(c.id).params) {
      if (p.field == nullptr) continue;
      set.push_back(p.field);
      const auto e =
          std::find_if(c.parameters.begin(), c.parameters.end(), [&](const Estimate& x) { return x.name == p.name; });
      ASSERT_NE(e, c.parameters.end()) << c.id;
      EXPECT_DOUBLE_EQ((*d.odometry_model).*(p.field), e->value) << c.id << "." << p.name;
    }
  }
  const OdometryModel nominal;
  for (const auto& c : cause_catalog()) {
    if (c.channel != "odometry") continue;
    for (const auto& p : c.params) {
      if (p.field == nullptr || std::find(set.begin(), set.end(), p.field) != set.end()) continue;
      EXPECT_EQ((*d.odometry_model).*(p.field), nominal.*(p.field)) << c.id << "." << p.name;
    }
  }
  // The distance scale at the generator's 0.3 m/s (velocity_scale or the speed-dependent one).
  EXPECT_NEAR(d.odometry_model->velocity_scale + d.odometry_model->speed_slope * 0.3, 1.05, 0.01);
  EXPECT_FALSE(d.landmark_model.has_value());
  EXPECT_TRUE(names_landmark_causes(d.not_testable));
}

TEST(LandmarkDiagnosis, ALogWithoutAMapIsNotTestableNotACrash) {
  sim::GeneratedLog g = velocity_log_with_landmarks({});
  g.log.landmark_map.clear();
  const Diagnosis d = diagnose_log(g.log);
  EXPECT_TRUE(names_landmark_causes(d.not_testable));
  EXPECT_FALSE(d.landmark_model.has_value());
  EXPECT_TRUE(std::none_of(d.causes.begin(), d.causes.end(), [](const Cause& c) { return c.channel == "landmark"; }));
}

TEST(LandmarkDiagnosis, FittedModelsReadStrictly) {
  LandmarkModel l;
  l.range_bias = 0.04;
  l.position_error_id = 9;
  nlohmann::json j = {{"landmark", l}};
  EXPECT_EQ(read_fitted_models(j).landmark->position_error_id, 9);
  j["landmark"]["range_bias_mm"] = 40;
  EXPECT_THROW(read_fitted_models(j), UsageError);
  EXPECT_THROW(read_fitted_models({{"landmarks", nlohmann::json::object()}}), UsageError);
  nlohmann::json bad = {{"landmark", l}};
  bad["landmark"]["sigma_range_m"] = -1.0;
  EXPECT_THROW(read_fitted_models(bad), UsageError);
  OdometryModel o;
  nlohmann::json oj = {{"odometry_kind", "encoder"}, {"odometry", o}};
  EXPECT_DOUBLE_EQ(read_fitted_models(oj).odometry->E_d, 1.0);
  oj["odometry_kind"] = "wheels";
  EXPECT_THROW(read_fitted_models(oj), UsageError);
}

}  // namespace
}  // namespace locbench::diagnosis
