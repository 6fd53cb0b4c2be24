// The landmark filter family on simulated logs with a hidden effect in the odometry: the model the
// diagnosis fits on the first half, run inside the filter, beats the nominal model on the second
// half; with nothing hidden the two are the same filter.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "algorithms/diagnosis/diagnosis.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "pipelines/filter_models.h"
#include "pipelines/landmark_family.h"

namespace locbench::experiments::landmarks {
namespace {

struct Family {
  std::vector<MethodScore> scores;
  FilterModels models;
  const MethodScore& of(Method m) const {
    for (const auto& s : scores)
      if (s.method == m) return s;
    throw std::logic_error("no such method");
  }
};

Family run_family(const std::vector<sim::HiddenEffect>& effects, std::uint64_t seed) {
  sim::GeneratorOptions g;
  g.velocity_odometry = true;
  g.compass = false;
  g.waypoints = 24;
  sim::GeneratedLog log = sim::generate_log(effects, seed, g);
  sim::LandmarkLogOptions l;
  l.sigma_range = 0.05;
  sim::add_landmark_observations(log, {}, seed + 1, l);
  const Log& full = log.log;
  const double from = std::max(full.odometry.front().t, full.truth.front().t);
  const double to = std::min(full.odometry.back().t, full.truth.back().t);
  const double mid = 0.5 * (from + to);
  const double b = full.nominal_model() ? full.nominal_model()->wheelbase : 0.3;
  const TrackingData train = tracking_data(full, from, mid, b), test = tracking_data(full, mid, to, b);
  LandmarkSensorModel sensor;
  Family f;
  f.models =
      filter_models(diagnosis::diagnose_log(restrict_log(full, from, mid)), measured_sensor_noise(train, sensor));
  FamilyOptions options;
  options.process_scales = {1.0 / 16.0, 0.25, 1.0, 4.0, 16.0};  // a smaller grid than the experiment's,
  options.r_scales = {1.0, 16.0, 256.0};                        // the same for every method
  options.sage_husa_forgetting = {0.9, 0.97, 0.99};
  options.vb_forgetting = {0.97, 0.99, 0.999};
  f.scores = tune_and_score(train, test, f.models, options);
  return f;
}

TEST(LandmarkFamily, TheDiagnosedVelocityScaleMakesTheFilterBetterThanTheNominalModel) {
  // The robot drives 15% farther and turns 10% more than its logged velocities say.
  const Family f = run_family({{"velocity_scale", 0.15}, {"turn_rate_scale", 0.10}}, 21);
  ASSERT_FALSE(f.models.causes.empty());
  EXPECT_NEAR(f.models.diagnosed_motion.velocity_scale, 1.15, 0.02);
  const TrackResult& nominal = f.of(Method::kNominalModel).heldout;
  const TrackResult& diagnosed = f.of(Method::kDiagnosedModel).heldout;
  for (const auto& s : f.scores) {
    EXPECT_TRUE(s.heldout.finite) << to_string(s.method);
    EXPECT_EQ(s.grid_runs, 15u) << "every method gets the same grid budget: 5 process scales × 3 second knobs";
  }
  EXPECT_FALSE(diagnosed.diverged);
  EXPECT_LT(diagnosed.position_rmse(), 0.8 * nominal.position_rmse())
      << "diagnosed " << diagnosed.position_rmse() << " m, nominal " << nominal.position_rmse() << " m";
}

TEST(LandmarkFamily, WithNothingHiddenTheDiagnosedModelIsTheNominalOne) {
  const Family f = run_family({}, 5);
  for (const std::string& c : f.models.causes) {
    EXPECT_EQ(c.rfind("landmark_", 0), std::string::npos) << "no landmark cause on a null log: " << c;
  }
  EXPECT_DOUBLE_EQ(f.models.diagnosed_motion.velocity_scale, 1.0);
  EXPECT_DOUBLE_EQ(f.models.diagnosed_motion.turn_rate_scale, 1.0);
  const double nominal = f.of(Method::kNominalModel).heldout.position_rmse();
  const double diagnosed = f.of(Method::kDiagnosedModel).heldout.position_rmse();
  EXPECT_NEAR(diagnosed, nominal, 0.2 * nominal);
  EXPECT_LT(nominal, 0.15);
}

TEST(LandmarkTuning, TheLogScoreIsLowestWhenTheCovarianceMatchesTheErrors) {
  // Errors of 0.1 m, 0.1 m, 0.1 rad on every axis; the filter reports P = c·diag(0.01): the
  // NEES is 3/c and the log score ½(3/c + ln det P), lowest at c = 1. An overconfident filter
  // (c = 1/10, NEES 30) and an underconfident one (c = 10, NEES 0.3) score worse.
  const auto score = [](double c) {
    TrackResult r;
    for (int i = 0; i < 100; ++i) {
      r.position_error.push_back(std::sqrt(0.02));
      r.nees.push_back(3.0 / c);
      r.log_det_covariance.push_back(std::log(std::pow(c * 0.01, 3)));
    }
    return r.log_score();
  };
  EXPECT_NEAR(score(1.0), 0.5 * (3.0 + 3.0 * std::log(0.01)), 1e-12);
  EXPECT_LT(score(1.0), score(0.1));
  EXPECT_LT(score(1.0), score(10.0));
  EXPECT_LT(score(1.0), score(0.8));
  EXPECT_LT(score(1.0), score(1.25));
}

TEST(LandmarkTuning, ADivergedRunHasAnInfiniteLogScore) {
  TrackResult r;
  r.position_error = {0.1};
  r.nees = {3.0};
  r.log_det_covariance = {-9.0};
  EXPECT_TRUE(std::isfinite(r.log_score()));
  r.diverged = true;
  EXPECT_EQ(r.log_score(), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace locbench::experiments::landmarks
