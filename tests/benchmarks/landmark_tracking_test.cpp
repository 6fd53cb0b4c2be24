// The landmark filter family on simulated logs with a hidden effect in the odometry: the model the
// diagnosis fits on the first half, run inside the filter, beats the nominal model on the second
// half; with nothing hidden the two are the same filter.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/statistics.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "pipelines/filter_models.h"
#include "pipelines/landmark_family.h"

namespace locbench::experiments::landmarks {
namespace {

struct Family {
  TrackingData test;
  std::vector<MethodScore> scores;
  FilterModels models;
  const MethodScore& of(Method m) const {
    for (const auto& s : scores)
      if (s.method == m) return s;
    throw std::logic_error("no such method");
  }
};

// Extra noise on the observations from `from` (true time) on: σ_r and σ_φ added in quadrature.
void add_sensor_noise_after(Log& log, double from, double range_sigma, double bearing_sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  for (LandmarkReading& r : log.landmarks) {
    if (r.t < from) continue;
    r.range += range_sigma * n(rng);
    r.bearing += bearing_sigma * n(rng);
  }
}

struct FamilyRun {
  double noise_after_half_m = 0.0;  // extra range noise late in the second half (bearing: /3 rad per m)
  bool track_noise_level = false;
};

FamilyOptions small_grid() {
  FamilyOptions options;
  options.process_scales = {1.0 / 16.0, 0.25, 1.0, 4.0, 16.0};  // a smaller grid than the experiment's,
  options.r_scales = {1.0, 16.0, 256.0};                        // the same for every method
  options.sage_husa_forgetting = {0.9, 0.97, 0.99};
  options.vb_forgetting = {0.97, 0.99, 0.999};
  return options;
}

Family run_family(const std::vector<sim::HiddenEffect>& effects, std::uint64_t seed, const FamilyRun& run = {}) {
  sim::GeneratorOptions g;
  g.velocity_odometry = true;
  g.compass = false;
  g.waypoints = 24;
  sim::GeneratedLog log = sim::generate_log(effects, seed, g);
  sim::LandmarkLogOptions l;
  l.sigma_range = 0.05;
  sim::add_landmark_observations(log, {}, seed + 1, l);
  Log& full = log.log;
  const double from = std::max(full.odometry.front().t, full.truth.front().t);
  const double to = std::min(full.odometry.back().t, full.truth.back().t);
  const double mid = 0.5 * (from + to);
  if (run.noise_after_half_m > 0.0)
    add_sensor_noise_after(full, mid + 0.25 * (to - mid), run.noise_after_half_m, run.noise_after_half_m / 3.0,
                           seed + 2);
  const double b = full.nominal_model() ? full.nominal_model()->wheelbase : 0.3;
  const TrackingData train = tracking_data(full, from, mid, b), test = tracking_data(full, mid, to, b);
  LandmarkSensorModel sensor;
  Family f;
  f.models =
      filter_models(diagnosis::diagnose_log(restrict_log(full, from, mid)), measured_sensor_noise(train, sensor));
  FamilyOptions options = small_grid();
  options.track_noise_level = run.track_noise_level;
  f.scores = tune_and_score(train, test, f.models, options);
  f.test = test;
  return f;
}

// The stall loss a filter carries, drawn as its Gauss–Markov process at 0.01 s over 20,000
// windows of 1 s: the windows' mean loss has the stall mixture's variance p(1 − p)f² and adjacent
// windows correlate as the twin's chain, (q − p)/(1 − p).
TEST(StallLossProcess, ItsWindowMeansHaveTheMixturesVarianceAndTheChainsCorrelation) {
  diagnosis::OdometryModel model;
  model.stall_rate = 0.1;      // p = 1 − e^(−0.1) = 0.095
  model.stall_duration = 0.6;  // f = 0.6
  const double window = 1.0, q = 0.5;
  const filters::GaussMarkovBias process = stall_loss_process(model, window, q);
  const double p = 1.0 - std::exp(-0.1), f = 0.6;

  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const double dt = 0.01, a = std::exp(-dt / process.time_s);
  double l = process.sigma * normal(rng);
  std::vector<double> means;
  for (int w = 0; w < 20000; ++w) {
    double sum = 0.0;
    for (int k = 0; k < 100; ++k) {
      l = a * l + process.sigma * std::sqrt(1.0 - a * a) * normal(rng);
      sum += l;
    }
    means.push_back(sum / 100.0);
  }
  double var = 0.0, cov = 0.0;
  for (std::size_t i = 0; i < means.size(); ++i) {
    var += means[i] * means[i];
    if (i > 0) cov += means[i] * means[i - 1];
  }
  var /= static_cast<double>(means.size());
  cov /= static_cast<double>(means.size() - 1);
  EXPECT_NEAR(var, p * (1.0 - p) * f * f, 0.06 * p * (1.0 - p) * f * f);  // 0.0309
  EXPECT_NEAR(cov / var, (q - p) / (1.0 - p), 0.03);                      // 0.448
}

TEST(StallLossProcess, WithoutPersistenceTheStallsAreAChainOfTheirOwnRateAndDuration) {
  diagnosis::OdometryModel model;
  model.stall_rate = 0.1;
  model.stall_duration = 0.6;
  EXPECT_NEAR(stall_loss_process(model, 1.0, 0.0).time_s, 1.0 / (0.1 + 1.0 / 0.6), 1e-12);
  EXPECT_EQ(stall_loss_process(diagnosis::OdometryModel{}, 1.0, 0.5).sigma, 0.0);
}

TEST(LandmarkTuning, ASettingRunOnTwoTuningPartsIsScoredOnBothJoined) {
  // The tuning part given twice, as two parts: each setting's steps are those of one part twice
  // over, so its RMSE, mean NEES and log score are those of one part, and the same settings win
  // (the NEES band is that of twice the duration, narrower, which picks the same setting here).
  // A short log and a 2 × 2 grid: the joining is what is tested.
  sim::GeneratorOptions g;
  g.velocity_odometry = true;
  g.compass = false;
  g.waypoints = 8;
  sim::GeneratedLog log = sim::generate_log({{"velocity_scale", 0.15}}, 21, g);
  sim::add_landmark_observations(log, {}, 22, {});
  const Log& full = log.log;
  const double from = std::max(full.odometry.front().t, full.truth.front().t);
  const double to = std::min(full.odometry.back().t, full.truth.back().t);
  const double mid = 0.5 * (from + to);
  const TrackingData train = tracking_data(full, from, mid, 0.3), test = tracking_data(full, mid, to, 0.3);
  const FilterModels models = filter_models(diagnosis::diagnose_log(restrict_log(full, from, mid)),
                                            measured_sensor_noise(train, LandmarkSensorModel{}));
  FamilyOptions options;
  options.process_scales = {0.25, 4.0};
  options.r_scales = {1.0, 16.0};
  options.sage_husa_forgetting = {0.95, 0.99};
  options.vb_forgetting = {0.97, 0.999};
  const std::vector<MethodScore> once = tune_and_score(train, test, models, options);
  const std::vector<MethodScore> twice = tune_and_score({{train, models}, {train, models}}, test, models, options);
  ASSERT_EQ(twice.size(), once.size());
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(b)); };
  int compared = 0;
  for (std::size_t i = 0; i < twice.size(); ++i) {
    EXPECT_EQ(twice[i].grid_runs, 4u);
    if (!std::isfinite(once[i].tuning_rmse)) continue;
    if (twice[i].process_scale != once[i].process_scale || twice[i].knob != once[i].knob) continue;
    ++compared;
    EXPECT_TRUE(near(twice[i].tuning_rmse, once[i].tuning_rmse)) << to_string(twice[i].method);
    EXPECT_TRUE(near(twice[i].tuning_nees, once[i].tuning_nees)) << to_string(twice[i].method);
    EXPECT_TRUE(near(twice[i].tuning_log_score, once[i].tuning_log_score)) << to_string(twice[i].method);
  }
  EXPECT_GE(compared, 5) << "methods at the same setting, not diverged";
  EXPECT_EQ(twice.back().process_scale, once.back().process_scale) << "the diagnosed model's setting";
  EXPECT_EQ(twice.back().knob, once.back().knob);
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

// |ln(NEES / 3)|: how far a 3-state NEES is from consistent, on a ratio scale.
double inconsistency(const TrackResult& r) { return std::abs(std::log(mean(r.nees) / 3.0)); }

TEST(LandmarkNoiseLevel, AFilterThatTracksTheLevelStaysConsistentWhenTheSensorGetsNoisier) {
  // A quarter into the held-out half the camera's range noise goes from 0.05 m to
  // √(0.05² + 0.3²) = 0.30 m and its bearing noise from 0.01 to 0.10 rad; the filters are tuned on
  // the first half. Untracked, the diagnosed model's filter trusts the noisier observations as before
  // and is over-confident; tracked, it scales its R by the innovations' level over the last minute
  // against the tuning half's. (With the change at the held-out half's very start it is not caught:
  // the first 20 innovations of a run have no level yet, and a filter thrown off by them recovers
  // slowly.)
  FamilyRun noisier{.noise_after_half_m = 0.3};
  const TrackResult untracked = run_family({}, 8, noisier).of(Method::kDiagnosedModel).heldout;
  noisier.track_noise_level = true;
  const Family tracked_family = run_family({}, 8, noisier);
  const MethodScore& tracked = tracked_family.of(Method::kDiagnosedModel);
  EXPECT_GT(tracked.level_reference.minCoeff(), 0.0) << "a reference level was measured on the tuning half";
  EXPECT_GT(mean(untracked.nees), 30.0) << "the untracked filter is over-confident";
  EXPECT_LT(mean(tracked.heldout.nees), 3.0 * 1.5);
  EXPECT_LT(inconsistency(tracked.heldout), 0.5 * inconsistency(untracked))
      << "NEES tracked " << mean(tracked.heldout.nees) << ", untracked " << mean(untracked.nees);
  EXPECT_LT(tracked.heldout.position_rmse(), 1.1 * untracked.position_rmse());
  EXPECT_EQ(tracked_family.of(Method::kNominalModel).level_reference.minCoeff(), 0.0)
      << "only the diagnosed model tracks the level";
}

TEST(LandmarkNoiseLevel, AtAConstantLevelTrackingChangesLittle) {
  const TrackResult untracked = run_family({}, 8).of(Method::kDiagnosedModel).heldout;
  const TrackResult tracked = run_family({}, 8, {.track_noise_level = true}).of(Method::kDiagnosedModel).heldout;
  EXPECT_NEAR(tracked.position_rmse(), untracked.position_rmse(), 0.15 * untracked.position_rmse());
  EXPECT_LT(std::abs(std::log(mean(tracked.nees) / mean(untracked.nees))), 0.3)
      << "NEES tracked " << mean(tracked.nees) << ", untracked " << mean(untracked.nees);
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

// A grid of three settings on a tuning part whose NEES band is [2.3, 3.8]: the lowest log score
// (−5.0) belongs to an overconfident setting (NEES 6.0); a consistent one (NEES 3.1) scores −4.0,
// another consistent one −3.0, and a diverged one has NEES 3.0 but no finite RMSE.
const filters::ChiSquareInterval kBand{2.3, 3.8};
const std::vector<GridRun> kGrid = {{.process_scale = 0.25, .knob = 4.0, .rmse = 0.10, .nees = 6.0, .log_score = -5.0},
                                    {.process_scale = 1.0, .knob = 4.0, .rmse = 0.12, .nees = 3.1, .log_score = -4.0},
                                    {.process_scale = 4.0, .knob = 4.0, .rmse = 0.15, .nees = 2.5, .log_score = -3.0},
                                    {.process_scale = 64.0,
                                     .knob = 4.0,
                                     .rmse = std::numeric_limits<double>::infinity(),
                                     .nees = 3.0,
                                     .log_score = std::numeric_limits<double>::infinity()}};

TEST(LandmarkTuning, TheConsistentLogScorePicksTheBestScoringSettingWhoseNeesIsInsideItsBand) {
  EXPECT_EQ(choose_setting(kGrid, kBand, TuningCriterion::kConsistentLogScore), 1u);
  EXPECT_EQ(choose_setting(kGrid, kBand, TuningCriterion::kLogScore), 0u) << "the plain log score ignores the band";
}

TEST(LandmarkTuning, WithNoConsistentSettingTheConsistentLogScoreFallsBackToTheLowestLogScore) {
  std::vector<GridRun> grid = kGrid;
  grid[1].nees = 5.0;
  grid[2].nees = 1.5;
  EXPECT_EQ(choose_setting(grid, kBand, TuningCriterion::kConsistentLogScore), 0u)
      << "the diverged setting's NEES of 3.0 does not make it consistent";
}

TEST(LandmarkTuning, TheRmseCriterionPicksTheLowestRmseAndAmongNearTiesTheConsistentOne) {
  EXPECT_EQ(choose_setting(kGrid, kBand, TuningCriterion::kRmse), 0u);
  EXPECT_EQ(choose_setting(kGrid, kBand, TuningCriterion::kRmse, 0.25), 1u) << "0.12 m is within 25% of 0.10 m";
}

}  // namespace
}  // namespace locbench::experiments::landmarks
