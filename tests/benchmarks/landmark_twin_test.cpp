// The landmark twin draws a log from a model; the diagnosis, run on the drawn log,
// gives the model back. The sensor twin keeps the log's motion and draws its observations. Its sensor draws the noise
// structure it is given, and the predictivity summary counts coverage, correlation and rank violations as defined.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "algorithms/diagnosis/diagnosis.h"
#include "core/angle.h"
#include "core/rng.h"
#include "core/statistics.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "pipelines/landmark_twin.h"
#include "pipelines/predictivity.h"

namespace locbench::experiments::landmarks {
namespace {

// A simulated landmark log with nothing hidden, and the tracking data of all of it.
struct Base {
  Log log;
  TrackingData data;
};
Base base_log(std::uint64_t seed) {
  sim::GeneratorOptions g;
  g.velocity_odometry = true;
  g.compass = false;
  g.waypoints = 24;
  sim::GeneratedLog generated = sim::generate_log({}, seed, g);
  sim::add_landmark_observations(generated, {}, seed + 1, {});
  Base b;
  b.log = generated.log;
  const double from = std::max(b.log.odometry.front().t, b.log.truth.front().t);
  const double to = std::min(b.log.odometry.back().t, b.log.truth.back().t);
  b.data = tracking_data(b.log, from, to, b.log.nominal_model() ? b.log.nominal_model()->wheelbase : 0.3);
  return b;
}

const diagnosis::Estimate* estimate(const diagnosis::Diagnosis& d, const std::string& cause) {
  for (const auto& c : d.causes)
    if (c.id == cause && c.detected && !c.parameters.empty()) return &c.parameters.front();
  return nullptr;
}

TEST(LandmarkTwin, TheDiagnosisOfATwinRecoversTheModelItWasDrawnFrom) {
  const Base b = base_log(41);
  diagnosis::OdometryModel model;
  model.velocity_scale = 1.12;
  model.turn_rate_scale = 0.93;
  model.sigma_x = 0.01, model.sigma_y = 0.005, model.sigma_theta = 0.004;
  const TrackingData twin = landmark_twin(b.data, model, LandmarkSensorModel{}, 7);
  Log drawn = b.log;
  drawn.truth = twin.motion.truth;  // the logged odometry, the twin's truth
  const diagnosis::Diagnosis d = diagnosis::diagnose_log(drawn);
  const diagnosis::Estimate* v = estimate(d, "velocity_scale");
  const diagnosis::Estimate* w = estimate(d, "turn_rate_scale");
  ASSERT_NE(v, nullptr) << d.verdict;
  ASSERT_NE(w, nullptr) << d.verdict;
  EXPECT_LE(v->lo, 1.12) << v->value;
  EXPECT_GE(v->hi, 1.12) << v->value;
  EXPECT_LE(w->lo, 0.93) << w->value;
  EXPECT_GE(w->hi, 0.93) << w->value;
  ASSERT_TRUE(d.odometry_model.has_value());
  EXPECT_NEAR(d.odometry_model->sigma_x, 0.01, 0.003) << "the floor per window the twin drew, fitted with the causes";
  EXPECT_NEAR(d.odometry_model->sigma_theta, 0.004, 0.0015);
}

TEST(LandmarkTwin, ANoiselessTwinOfTheNominalModelFollowsTheLoggedOdometry) {
  const Base b = base_log(43);
  diagnosis::OdometryModel model;
  model.sigma_x = model.sigma_y = model.sigma_theta = 0.0;
  const TrackingData twin = landmark_twin(b.data, model, LandmarkSensorModel{}, 1);
  // The generator's own truth differs from the logged odometry by its noise; the twin's does not:
  // its windows' residuals under the nominal model vanish.
  double worst = 0.0;
  for (const auto& w : twin.motion.windows) {
    const auto r = diagnosis::window_residual(twin.motion, w, diagnosis::OdometryModel{});
    if (r.valid) worst = std::max(worst, r.r.head<2>().norm());
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(twin.observations.size(), b.data.observations.size()) << "the same observation schedule";
}

TEST(LandmarkTwin, ItsSensorDrawsTheNoiseStructureItIsGiven) {
  const Base b = base_log(45);
  LandmarkSensorModel sensor;
  sensor.range_sigma = 0.08;
  sensor.bearing_sigma = 0.01;
  sensor.structure.range_landmark_sigma = 0.05;
  sensor.structure.range_correlation = {0.5, 5.0};
  diagnosis::OdometryModel still;
  still.sigma_x = still.sigma_y = still.sigma_theta = 0.0;
  const TrackingData twin = landmark_twin(b.data, still, sensor, 3);
  const LandmarkSensorModel measured = measured_sensor_noise(twin, LandmarkSensorModel{});
  EXPECT_NEAR(measured.range_sigma, 0.08 * std::sqrt(1.0 + 0.05 * 0.05 / (0.08 * 0.08)), 0.03);
  EXPECT_NEAR(measured.bearing_sigma, 0.01, 0.0015);
  EXPECT_GT(measured.structure.range_correlation.share, 0.2) << "half the range variance is correlated";
  EXPECT_LT(measured.structure.bearing_correlation.share, 0.1) << "bearing noise was drawn white";
  EXPECT_LT(measured.structure.range_level_sigma, 0.15) << "one noise level throughout";
  // A level that varies: the range σ of each minute times e^(0.6·N(0, 1)).
  sensor.structure.range_level_sigma = 0.6;
  const TrackingData varying = landmark_twin(b.data, still, sensor, 3);
  EXPECT_GT(measured_sensor_noise(varying, LandmarkSensorModel{}).structure.range_level_sigma, 0.3)
      << (b.data.to - b.data.from) << " s";
}

// The sensor twin is the log with only its landmark observations drawn anew: the log's odometry and
// truth unchanged; with a noiseless sensor every observation of the log is drawn again, at its time
// and of its landmark, at the range and bearing the log's truth sees it from (the simulated log's
// own observations differ by their noise, 5 cm and 0.02 rad); with a noisy one the noise is the
// sensor's.
TEST(LandmarkSensorTwin, KeepsTheLogsMotionAndDrawsItsObservationsFromTheLogsTruth) {
  const Base b = base_log(55);
  LandmarkSensorModel noiseless;
  noiseless.range_sigma = noiseless.bearing_sigma = 0.0;
  const TrackingData clean = landmark_sensor_twin(b.data, noiseless, 2);
  ASSERT_EQ(clean.motion.steps.size(), b.data.motion.steps.size());
  for (std::size_t i = 0; i < clean.motion.steps.size(); ++i) {
    EXPECT_EQ(clean.motion.steps[i].a, b.data.motion.steps[i].a);
    EXPECT_EQ(clean.motion.steps[i].b, b.data.motion.steps[i].b);
  }
  ASSERT_EQ(clean.motion.truth.size(), b.data.motion.truth.size());
  EXPECT_EQ(clean.motion.truth.back().pose.x, b.data.motion.truth.back().pose.x);
  ASSERT_EQ(clean.observations.size(), b.data.observations.size()) << "every landmark the log saw is in reach";
  diagnosis::TruthInterpolator at(b.data.motion.truth);
  double worst_range = 0.0, worst_bearing = 0.0, logged_range = 0.0;
  for (std::size_t i = 0; i < clean.observations.size(); ++i) {
    const Observation &z = clean.observations[i], &o = b.data.observations[i];
    ASSERT_EQ(z.t, o.t);
    ASSERT_EQ(z.id, o.id);
    const auto p = at.at(z.t);
    ASSERT_TRUE(p.has_value());
    const Eigen::Vector2d l = b.data.map.at(z.id);
    const double rho = std::hypot(l.x() - p->x, l.y() - p->y);
    worst_range = std::max(worst_range, std::abs(z.range - rho));
    worst_bearing =
        std::max(worst_bearing, std::abs(angle_diff(z.bearing, std::atan2(l.y() - p->y, l.x() - p->x) - p->theta)));
    logged_range = std::max(logged_range, std::abs(o.range - rho));
  }
  EXPECT_LT(worst_range, 1e-9);
  EXPECT_LT(worst_bearing, 1e-9);
  EXPECT_GT(logged_range, 0.05) << "the log's own observations carry its noise";
  LandmarkSensorModel noisy;
  noisy.range_sigma = 0.08;
  noisy.bearing_sigma = 0.01;
  const LandmarkSensorModel measured =
      measured_sensor_noise(landmark_sensor_twin(b.data, noisy, 2), LandmarkSensorModel{});
  EXPECT_NEAR(measured.range_sigma, 0.08, 0.01);
  EXPECT_NEAR(measured.bearing_sigma, 0.01, 0.0015);
}

// Gross outliers: the twin replaces 2% of its observations by residuals resampled from the given
// ones (a range 12 σ long, a bearing 0.4 rad off), and the share is measured back (mean of 8
// twins of ~1,230 observations); with normal noise alone (P beyond 5σ: 6e-7 per channel) none are
// measured.
TEST(LandmarkTwin, GrossOutliersItDrawsAreMeasuredBackAndNormalNoiseHasNone) {
  const Base b = base_log(51);
  LandmarkSensorModel sensor;
  sensor.range_sigma = 0.05;
  sensor.bearing_sigma = 0.01;
  diagnosis::OdometryModel still;
  still.sigma_x = still.sigma_y = still.sigma_theta = 0.0;
  const LandmarkSensorModel clean = measured_sensor_noise(landmark_twin(b.data, still, sensor, 9), sensor);
  EXPECT_EQ(clean.structure.outlier_rate, 0.0);
  EXPECT_TRUE(clean.structure.outliers.empty());
  sensor.structure.outlier_rate = 0.02;
  sensor.structure.outliers = {{12.0, 0.0}, {0.0, 0.4}};
  double rate = 0.0;
  for (std::uint64_t seed = 9; seed < 17; ++seed) {
    const LandmarkSensorModel m = measured_sensor_noise(landmark_twin(b.data, still, sensor, seed), sensor);
    rate += m.structure.outlier_rate / 8.0;
  }
  EXPECT_NEAR(rate, 0.02, 0.004);
  const TrackingData twin = landmark_twin(b.data, still, sensor, 9);
  const LandmarkSensorModel measured = measured_sensor_noise(twin, sensor);  // residuals in units of its σ_r
  ASSERT_FALSE(measured.structure.outliers.empty());
  for (const Eigen::Vector2d& e : measured.structure.outliers)
    EXPECT_TRUE(std::abs(e.x() - 12.0) < 4.0 || std::abs(e.y() - 0.4) < 0.05) << e.transpose();
}

// A twin whose velocity scale is 25% off drifts far from the log's path. Its camera still keeps
// the log's frames (times, and as many landmarks per frame), but sees only landmarks within the
// reach the log's observations show (the simulated camera's |bearing| ≤ 0.5 rad and range ≤ 6 m,
// as observed: with their noise) from the twin's own pose: the log's landmarks where they are in
// view, others in view where not.
TEST(LandmarkTwin, ItsCameraSeesOnlyWhatIsInReachFromTheTwinsPose) {
  const Base b = base_log(49);
  diagnosis::OdometryModel model;
  model.velocity_scale = 1.25;
  model.sigma_x = model.sigma_y = 0.01;
  model.sigma_theta = 0.005;
  const TrackingData twin = landmark_twin(b.data, model, LandmarkSensorModel{}, 5);
  diagnosis::TruthInterpolator at(twin.motion.truth);
  double reach_bearing = 0.0, reach_range = 0.0;
  for (const Observation& o : b.data.observations) {
    reach_bearing = std::max(reach_bearing, std::abs(o.bearing));
    reach_range = std::max(reach_range, o.range);
  }
  EXPECT_NEAR(reach_bearing, 0.5, 0.05);
  double widest = 0.0, farthest = 0.0;
  std::size_t kept = 0, beyond_before = 0;
  for (const Observation& o : twin.observations) {
    const auto p = at.at(o.t);
    ASSERT_TRUE(p.has_value());
    const Eigen::Vector2d l = b.data.map.at(o.id);
    widest = std::max(widest, std::abs(wrap_angle(std::atan2(l.y() - p->y, l.x() - p->x) - p->theta)));
    farthest = std::max(farthest, std::hypot(l.x() - p->x, l.y() - p->y));
  }
  for (std::size_t i = 0; i < b.data.observations.size(); ++i) {
    const Observation& o = b.data.observations[i];
    const auto p = at.at(o.t);
    if (!p) continue;
    const Eigen::Vector2d l = b.data.map.at(o.id);
    if (std::abs(wrap_angle(std::atan2(l.y() - p->y, l.x() - p->x) - p->theta)) > reach_bearing) ++beyond_before;
    for (const Observation& z : twin.observations)
      if (z.t == o.t && z.id == o.id) ++kept;
  }
  EXPECT_LE(widest, reach_bearing);
  EXPECT_LE(farthest, reach_range);
  EXPECT_GT(beyond_before, b.data.observations.size() / 10) << "the log's schedule from the drifted pose";
  EXPECT_LE(twin.observations.size(), b.data.observations.size());
  EXPECT_GT(twin.observations.size(), b.data.observations.size() / 2) << kept << " kept as the log saw them";
}

// A twin whose heading wanders (σ_θ 0.02 rad per 1 s window, a random walk of ~0.3 rad over
// its few minutes) replayed open loop drifts off the log's path and its camera loses part of the
// log's view; steered toward the path with a 40 s time constant it stays near it and keeps the view.
TEST(LandmarkTwin, ASteeredTwinStaysOnTheLogsPathAndKeepsTheLogsView) {
  const Base b = base_log(49);
  diagnosis::OdometryModel model;
  model.sigma_x = model.sigma_y = 0.01;
  model.sigma_theta = 0.02;
  const auto off_path = [&](const TrackingData& twin) {
    diagnosis::TruthInterpolator at(twin.motion.truth);
    double sum = 0.0;
    std::size_t n = 0;
    for (const TruePose& p : b.data.motion.truth)
      if (const auto q = at.at(p.t)) sum += std::pow(q->x - p.pose.x, 2) + std::pow(q->y - p.pose.y, 2), ++n;
    return std::sqrt(sum / static_cast<double>(n));
  };
  const TrackingData open = landmark_twin(b.data, model, LandmarkSensorModel{}, 5);
  const TrackingData steered = landmark_twin(b.data, model, LandmarkSensorModel{}, 5, {}, 40.0);
  const double seen = static_cast<double>(b.data.observations.size());
  EXPECT_GT(off_path(open), 0.6);                       // 0.82 m, 94% of the view (seed 5)
  EXPECT_LT(off_path(steered), 0.4) << off_path(open);  // 0.28 m, 98.7%
  EXPECT_GT(off_path(open), 2.0 * off_path(steered));
  EXPECT_LT(static_cast<double>(open.observations.size()) / seen, 0.96);
  EXPECT_GT(static_cast<double>(steered.observations.size()) / seen, 0.97);
}

// Steering changes the twin's commands, not its model: the twin's truth against the model applied
// to the twin's own (steered) commands has the model's window variance (standardized residuals of
// mean square 1), a window that stands keeps its zero commands, one that turns in place keeps a
// zero translation, and every command is finite.
TEST(LandmarkTwin, ASteeredTwinIsStillTheModelAppliedToItsOwnCommands) {
  const Base b = base_log(57);
  diagnosis::OdometryModel model;
  model.velocity_scale = 1.1;
  model.sigma_x = 0.01, model.sigma_y = 0.006, model.sigma_theta = 0.004;
  const TrackingData twin = landmark_twin(b.data, model, LandmarkSensorModel{}, 3, {}, 20.0);
  Eigen::Vector3d squares = Eigen::Vector3d::Zero();
  std::size_t windows = 0, steered = 0;
  for (const diagnosis::MotionWindow& w : twin.motion.windows) {
    const diagnosis::WindowResidual r = diagnosis::window_residual(twin.motion, w, model);
    if (!r.valid || r.heading_only) continue;
    squares += r.r.cwiseAbs2().cwiseQuotient(r.variance);
    ++windows;
  }
  for (std::size_t i = 0; i < twin.motion.steps.size(); ++i) {
    const diagnosis::OdometryStep &s = twin.motion.steps[i], &o = b.data.motion.steps[i];
    ASSERT_TRUE(std::isfinite(s.a) && std::isfinite(s.b)) << i;
    if (o.a == 0.0) {
      EXPECT_EQ(s.a, 0.0) << i;
    }
    if (o.a == 0.0 && o.b == 0.0) {
      EXPECT_EQ(s.b, 0.0) << i;
    }
    steered += s.a != o.a || s.b != o.b ? 1 : 0;
  }
  ASSERT_GT(windows, 200u);
  EXPECT_GT(steered, twin.motion.steps.size() / 4) << "most moving steps are corrected";
  const Eigen::Vector3d mean_square = squares / static_cast<double>(windows);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_square(c), 1.0, 0.15) << c;
}

// A motion noise level drawn anew every 60 s, e^(0.5·N(0, 1)) common to the three components, is
// measured back from the twin's window residuals; a twin without it measures near none.
TEST(LandmarkTwin, AMotionNoiseLevelMovingBetweenBlocksIsMeasuredBack) {
  const Base b = base_log(59);
  diagnosis::OdometryModel model;
  model.sigma_x = model.sigma_y = 0.006;
  model.sigma_theta = 0.003;
  MotionNoiseStructure moving;
  moving.level_spread = {0.5, 0.5, 0.5};
  Eigen::Vector3d measured = Eigen::Vector3d::Zero(), none = Eigen::Vector3d::Zero();
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    measured +=
        fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, moving).motion, model).level_spread / 4.0;
    none += fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, {}).motion, model).level_spread / 4.0;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(measured(c), 0.5, 0.15) << c;
    EXPECT_LT(none(c), 0.1) << c;
  }
}

// Stalls that go on into the next window (a robot pushing against something for seconds) are
// drawn as a chain with the mixture's stall probability p per window, and the persistence
// q = P(stall | stall before) is measured back from the stall posteriors of adjacent windows;
// independent stalls measure about p.
TEST(LandmarkTwin, TheStallPersistenceItDrawsIsMeasuredBack) {
  const Base b = base_log(47);
  diagnosis::OdometryModel model;
  model.stall_rate = 0.3;  // p = 1 − e^(−0.3) = 0.26 per 1 s window
  model.stall_duration = 0.6;
  model.sigma_x = model.sigma_y = 0.004;
  model.sigma_theta = 0.002;
  const double p = 1.0 - std::exp(-0.3);
  MotionNoiseStructure persistent;
  persistent.stall_persistence = 0.7;
  double in_runs = 0.0, independent = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    in_runs +=
        fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, persistent).motion, model).stall_persistence /
        4.0;
    independent +=
        fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, {}).motion, model).stall_persistence / 4.0;
  }
  EXPECT_NEAR(in_runs, 0.7, 0.12) << independent;
  EXPECT_NEAR(independent, p, 0.1) << in_runs;
  EXPECT_GT(in_runs - independent, 0.3);
}

// A turn-rate bias drawn anew every 60 s with spread 0.01 rad/s (σ_θ 2 mrad per 1 s window: a
// block's mean rate has a sampling error of ~0.3 mrad/s) is measured back from the twin's window
// residuals; a twin without it, with its heading noise 30% correlated over 5 s, shows none.
TEST(LandmarkTwin, ATurnRateBiasMovingBetweenBlocksIsMeasuredBackAndCorrelatedNoiseIsNotOne) {
  const Base b = base_log(53);
  diagnosis::OdometryModel model;
  model.sigma_x = model.sigma_y = 0.004;
  model.sigma_theta = 0.002;
  MotionNoiseStructure moving;
  moving.turn_bias_spread = 0.01;
  MotionNoiseStructure correlated;
  correlated.theta = {0.3, 5.0};
  double measured = 0.0, none = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    measured +=
        fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, moving).motion, model).turn_bias_spread / 4.0;
    none +=
        fit_motion_noise_structure(landmark_twin(b.data, model, {}, seed, correlated).motion, model).turn_bias_spread /
        4.0;
  }
  EXPECT_NEAR(measured, 0.01, 0.004) << none;
  EXPECT_LT(none, 0.001) << measured;
}

// Beyond 4σ: −5, +6 and −4.5; the first run goes on over −3 and −2.5 (same sign, beyond 2σ), the
// second stops at +1, the third at the gap before −3.
TEST(LargeResidualRuns, CountsTheTailWindowsTheirSignAndHowLongTheirRunsLast) {
  const std::vector<double> z{0.1, -5.0, -3.0, -2.5, 0.2, 6.0, 1.0, -4.5, -3.0};
  const std::vector<bool> adjacent{false, true, true, true, true, true, true, true, false};
  const LargeResidualRuns r = large_residual_runs(z, adjacent);
  double squares = 0.0;
  for (double v : z) squares += v * v;
  EXPECT_EQ(r.windows, 3u);
  EXPECT_DOUBLE_EQ(r.share_of_squares, (25.0 + 36.0 + 20.25) / squares);
  EXPECT_DOUBLE_EQ(r.negative_fraction, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.mean_run_windows, 5.0 / 3.0);  // runs of 3, 1 and 1 windows
  EXPECT_EQ(large_residual_runs({0.5, -1.0}, {false, true}).windows, 0u);
  // Independent Student-t tails (ν = 3): runs of about one window, half of them negative.
  Rng rng(11);
  std::vector<double> t(20000);
  for (double& v : t) v = rng.student_t(3.0);
  const LargeResidualRuns independent = large_residual_runs(t, std::vector<bool>(t.size(), true));
  EXPECT_GT(independent.windows, 300u);
  EXPECT_NEAR(independent.negative_fraction, 0.5, 0.07);
  EXPECT_LT(independent.mean_run_windows, 1.2);
}

TEST(NoiseCorrelation, AGaussMarkovShareAndTimeAreRecovered) {
  Rng rng(5);
  std::vector<double> t, r;
  double b = 0.0;
  for (int i = 0; i < 6000; ++i) {
    t.push_back(0.2 * i);
    const double a = std::exp(-0.2 / 4.0);  // τ = 4 s at 0.2 s per observation
    b = a * b + std::sqrt(1.0 - a * a) * rng.normal();
    r.push_back(std::sqrt(0.6) * rng.normal() + std::sqrt(0.4) * b);
  }
  const NoiseCorrelation c = fit_noise_correlation(t, r);
  EXPECT_NEAR(c.share, 0.4, 0.1);
  EXPECT_NEAR(c.time_s, 4.0, 1.5);
}

// Residuals with a fast and a slow part (τ 0.2 s and 30 s): one Gauss–Markov process cannot be
// both, and the fit is made for what a filter averaging observations sees — the variance of 10 s
// means drawn from the fitted model matches the data's. (The fit on the first 20 lags drew 0.71 of
// the data's here, and 0.5 on MRCLAM robot 3.)
TEST(NoiseCorrelation, TheFittedModelDrawsTheVarianceOfTenSecondMeans) {
  const auto draw = [](double white, std::vector<std::pair<double, double>> parts, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<double> r, state(parts.size(), 0.0);
    for (int i = 0; i < 18000; ++i) {
      double v = std::sqrt(white) * rng.normal();
      for (std::size_t k = 0; k < parts.size(); ++k) {
        const double a = std::exp(-0.1 / parts[k].second);
        state[k] = a * state[k] + std::sqrt(1.0 - a * a) * rng.normal();
        v += std::sqrt(parts[k].first) * state[k];
      }
      r.push_back(v);
    }
    return r;
  };
  const auto ten_second_ratio = [](const std::vector<double>& r) {  // var(10 s means) / var
    std::vector<double> means;
    for (std::size_t i = 0; i + 100 <= r.size(); i += 100)
      means.push_back(std::accumulate(r.begin() + i, r.begin() + i + 100, 0.0) / 100.0);
    return sample_variance(means) / sample_variance(r);
  };
  std::vector<double> t;
  for (int i = 0; i < 18000; ++i) t.push_back(0.1 * i);
  const std::vector<double> data = draw(0.3, {{0.6, 0.2}, {0.1, 30.0}}, 7);
  const NoiseCorrelation c = fit_noise_correlation(t, data);
  const std::vector<double> model = draw(1.0 - c.share, {{c.share, c.time_s}}, 8);
  EXPECT_NEAR(ten_second_ratio(model) / ten_second_ratio(data), 1.0, 0.2)
      << "fitted share " << c.share << ", τ " << c.time_s << " s";
  EXPECT_LE(c.time_s, 30.0);  // never beyond the longest block
}

// Three landmarks per camera frame, each with its own white noise (0.5 of the variance) and a part
// common to the frame that is correlated in time (0.5, τ 3 s). Within a frame only the white part
// differs, which measures the share; blocks of time means alone cannot tell a fast correlated
// part from white noise.
TEST(NoiseCorrelation, TheShareIsMeasuredWithinCameraFrames) {
  Rng rng(9);
  std::vector<double> t, r;
  double b = 0.0;
  const double a = std::exp(-0.25 / 3.0);
  for (int frame = 0; frame < 2000; ++frame) {
    b = a * b + std::sqrt(1.0 - a * a) * rng.normal();
    for (int k = 0; k < 3; ++k) t.push_back(0.25 * frame), r.push_back(std::sqrt(0.5) * (rng.normal() + b));
  }
  const NoiseCorrelation c = fit_noise_correlation(t, r);
  EXPECT_NEAR(c.share, 0.5, 0.05);
  EXPECT_NEAR(c.time_s, 3.0, 1.0);
}

TEST(NoiseCorrelation, WhiteNoiseInCameraFramesHasNone) {
  Rng rng(10);
  std::vector<double> t, r;
  for (int frame = 0; frame < 2000; ++frame)
    for (int k = 0; k < 3; ++k) t.push_back(0.25 * frame), r.push_back(rng.normal());
  EXPECT_LT(fit_noise_correlation(t, r).share, 0.05);
}

// Residuals whose σ changes every minute by a factor e^(0.5·N(0, 1)) give a level spread near
// 0.5; a constant σ gives one near 0 (the sampling spread of 60 s blocks of 300 residuals is
// removed).
TEST(NoiseLevelSpread, ALevelThatChangesEveryMinuteIsMeasuredAndAConstantOneIsNot) {
  Rng rng(11);
  std::vector<double> t, varying, constant;
  double level = 1.0;
  for (int i = 0; i < 60 * 5 * 30; ++i) {  // 30 minutes at 5 Hz
    if (i % 300 == 0) level = std::exp(0.5 * rng.normal());
    t.push_back(0.2 * i);
    varying.push_back(level * rng.normal());
    constant.push_back(rng.normal());
  }
  EXPECT_NEAR(noise_level_spread(t, varying), 0.5, 0.15);
  EXPECT_LT(noise_level_spread(t, constant), 0.05);
}

TEST(NoiseCorrelation, WhiteNoiseHasNone) {
  Rng rng(6);
  std::vector<double> t, r;
  for (int i = 0; i < 6000; ++i) t.push_back(0.2 * i), r.push_back(rng.normal());
  EXPECT_LT(fit_noise_correlation(t, r).share, 0.05);
}

PredictivityCell cell(const std::string& log, const std::string& method, double real, double nominal, double extended) {
  PredictivityCell c;
  c.log = log;
  c.method = method;
  c.real = real;
  c.nominal = {nominal * 0.9, nominal, nominal * 1.1, 20};
  c.extended = {extended * 0.9, extended, extended * 1.1, 20};
  return c;
}

TEST(Predictivity, CoverageCorrelationAndRankViolationsAreCountedPerMetric) {
  // Log A: real 1, 2, 4. The nominal twin swaps the first two (predicts 2.1, 1.0), the extended
  // twin ranks them right. Log B: both rank right.
  const std::vector<PredictivityCell> cells = {cell("A", "m1", 1.0, 2.1, 1.0), cell("A", "m2", 2.0, 1.0, 2.05),
                                               cell("A", "m3", 4.0, 4.0, 4.3), cell("B", "m1", 1.0, 1.0, 1.0),
                                               cell("B", "m2", 3.0, 3.0, 2.9)};
  const MetricPredictivity m = predictivity(cells);
  EXPECT_EQ(m.cells, 5u);
  EXPECT_EQ(m.compared, 5u);
  EXPECT_TRUE(m.log_scale);
  EXPECT_EQ(m.extended.covered, 5u);
  EXPECT_EQ(m.nominal.covered, 3u) << "A's m1 (2.1 ± 10%) and m2 (1.0 ± 10%) miss";
  EXPECT_EQ(m.nominal.below, 1u) << "A's m1: real 1 below [1.89, 2.31]";
  EXPECT_EQ(m.nominal.above, 1u) << "A's m2: real 2 above [0.9, 1.1]";
  EXPECT_EQ(m.extended.above + m.extended.below, 0u);
  // Nominal on A: m1 and m2 swapped, |1 − 2| / mean(1, 2, 4) = 3/7 for each of them, 0 for m3:
  // MMRV_A = (2 · 3/7) / 3; MMRV_B = 0; the mean over logs is 1/7.
  EXPECT_NEAR(m.nominal.mmrv, 1.0 / 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.extended.mmrv, 0.0);
  EXPECT_GT(m.extended.pearson, 0.99);
  EXPECT_LT(m.nominal.pearson, m.extended.pearson);
  EXPECT_DOUBLE_EQ(m.extended.spearman, 1.0);
}

// The sensor twin splits the extended twin's misses: a miss the sensor twin covers is the motion
// model's, one it misses too is the sensor model's; cells without a sensor twin (dead reckoning)
// are in neither count.
TEST(Predictivity, TheSensorTwinTellsAMissOfTheMotionModelFromOneOfTheSensorModel) {
  std::vector<PredictivityCell> cells = {cell("A", "motion", 1.0, 1.0, 2.0), cell("A", "sensor", 1.0, 1.0, 2.0),
                                         cell("A", "held", 1.0, 1.0, 1.0), cell("A", "dead_reckoning", 1.0, 1.0, 2.0)};
  cells[0].sensor = PredictiveInterval{0.95, 1.0, 1.05, 20};
  cells[1].sensor = PredictiveInterval{1.5, 1.6, 1.7, 20};
  cells[2].sensor = PredictiveInterval{0.9, 1.0, 1.1, 20};
  const MetricPredictivity m = predictivity(cells);
  EXPECT_EQ(m.extended.covered, 1u);
  EXPECT_EQ(m.sensor_cells, 3u);
  EXPECT_EQ(m.sensor_covered, 2u);
  EXPECT_EQ(m.extended_misses_of_motion, 1u);
  EXPECT_EQ(m.extended_misses_of_sensor, 1u) << "dead reckoning's miss has no sensor twin to tell";
}

// A NEES above its band [2.3, 3.8]: the sensor twin (the log's own motion, the fitted sensor)
// already above it names the motion; one staying inside names the sensor; one straddling the
// bound, both. Below the band, the same mirrored; inside it, nothing to explain.
TEST(Predictivity, TheSensorTwinNamesWhatPutsANeesOutsideItsBand) {
  EXPECT_EQ(excess_source(5.0, 2.3, 3.8, {4.0, 4.5, 5.5, 20}), "motion");
  EXPECT_EQ(excess_source(5.0, 2.3, 3.8, {1.3, 1.9, 2.6, 20}), "sensor");
  EXPECT_EQ(excess_source(5.0, 2.3, 3.8, {2.2, 3.4, 5.5, 20}), "both");
  EXPECT_EQ(excess_source(2.0, 2.3, 3.8, {1.3, 1.9, 2.6, 20}), "motion");
  EXPECT_EQ(excess_source(2.0, 2.3, 3.8, {2.5, 3.0, 3.5, 20}), "sensor");
  EXPECT_EQ(excess_source(3.0, 2.3, 3.8, {4.0, 4.5, 5.5, 20}), "");
}

TEST(Predictivity, ANonFiniteCellIsCountedButNotCorrelated) {
  std::vector<PredictivityCell> cells = {cell("A", "m1", 1.0, 1.0, 1.0), cell("A", "m2", 2.0, 2.0, 2.0),
                                         cell("A", "m3", 3.0, 3.0, 3.0)};
  cells.push_back(cell("A", "diverged", 5.0, 5.0, 5.0));
  cells.back().extended = predictive_interval({1.0, INFINITY, INFINITY});
  const MetricPredictivity m = predictivity(cells);
  EXPECT_EQ(m.cells, 4u);
  EXPECT_EQ(m.compared, 3u);
  EXPECT_EQ(cells.back().extended.high, INFINITY) << "two infinities interpolate to infinity, not NaN";
}

TEST(Predictivity, ACellWhoseRealRunDivergedIsCountedButNotCorrelated) {
  std::vector<PredictivityCell> cells = {cell("A", "m1", 1.0, 1.0, 1.0), cell("A", "m2", 2.0, 2.0, 2.0),
                                         cell("A", "lost", 1e11, 1e3, 1e12)};
  cells.back().real_diverged = true;
  const MetricPredictivity m = predictivity(cells);
  EXPECT_EQ(m.cells, 3u);
  EXPECT_EQ(m.compared, 2u);
  EXPECT_EQ(m.extended.covered, 2u) << "coverage still counts every cell";
}

}  // namespace
}  // namespace locbench::experiments::landmarks
