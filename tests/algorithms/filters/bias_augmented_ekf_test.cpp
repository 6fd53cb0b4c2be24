// The fitted-model EKF with the sensor's and the motion's correlated noise as Gauss–Markov states:
// without them it is MotionModelEkf; with a slowly wandering range bias hidden in the
// observations it finds the bias and keeps the pose where the plain filter is pulled off; with a
// motion error that persists for seconds its covariance grows across gaps in the observations as
// the error does, where the plain filter's white noise of the same 1 s variance falls short.
#include "algorithms/filters/bias_augmented_ekf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "algorithms/filters/consistency.h"
#include "algorithms/filters/motion_model_ekf.h"
#include "core/errors.h"
#include "core/rng.h"

namespace locbench::filters {
namespace {

constexpr double kWheelbase = 0.26;
const Eigen::Vector2d kLandmarks[] = {{3.0, 0.0}, {-3.0, 0.0}, {0.0, 3.0}, {0.0, -3.0}};

struct Step {
  WheelDisplacement u;
  Pose2 truth;
  std::vector<LandmarkRangeBearing> seen;
};

// 120 s on a circle of radius 1.5 m at 0.2 m/s, 10 steps per second, all four landmarks seen
// every second with white noise σ_r = 2 cm, σ_φ = 0.01 rad, plus a range bias common to the frame
// that wanders as a Gauss–Markov process of σ `bias_sigma`, τ 20 s, starting at +`bias_start`.
std::vector<Step> circle_run(double bias_sigma, double bias_start, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Step> out;
  Pose2 truth(0.0, -1.5, 0.0);
  const double v = 0.2, w = v / 1.5, dt = 0.1;
  double bias = bias_start;
  const double a = std::exp(-1.0 / 20.0);
  for (int k = 1; k <= 1200; ++k) {
    const double d = v * dt, th = w * dt;
    const WheelDisplacement exact{d - 0.5 * kWheelbase * th, d + 0.5 * kWheelbase * th};
    truth = odometry_step(truth, exact, kWheelbase);
    Step s;
    s.u = {exact.left + 0.0005 * rng.normal(), exact.right + 0.0005 * rng.normal()};
    s.truth = truth;
    if (k % 10 == 0) {
      bias = a * bias + std::sqrt(1.0 - a * a) * bias_sigma * rng.normal();
      for (const auto& m : kLandmarks) {
        const double dx = m.x() - truth.x, dy = m.y() - truth.y;
        s.seen.push_back({std::hypot(dx, dy) + bias + 0.02 * rng.normal(),
                          wrap_angle(std::atan2(dy, dx) - truth.theta + 0.01 * rng.normal()), m.x(), m.y(), 0.02 * 0.02,
                          0.01 * 0.01});
      }
    }
    out.push_back(s);
  }
  return out;
}

const Matrix3 kBody = Vector3(1e-5, 1e-5, 1e-5).asDiagonal();
const Matrix3 kStart = Matrix3::Identity() * 1e-4;

TEST(BiasAugmentedEkf, WithoutBiasItIsTheMotionModelEkf) {
  const auto run = circle_run(0.0, 0.0, 1);
  MotionModelEkf plain(kWheelbase, Pose2(0.0, -1.5, 0.0), kStart);
  BiasAugmentedEkf augmented(kWheelbase, Pose2(0.0, -1.5, 0.0), kStart, {});
  for (const Step& s : run) {
    plain.predict(s.u, kBody);
    augmented.predict(s.u, kBody, 0.1);
    for (const auto& z : s.seen) {
      EXPECT_EQ(plain.update(z, 13.8).gated, augmented.update(z, 13.8).gated);
    }
  }
  EXPECT_LT((plain.mean() - augmented.mean()).norm(), 1e-9);
  EXPECT_LT((plain.covariance() - augmented.covariance()).norm(), 1e-12);
  EXPECT_EQ(augmented.bias(), Eigen::Vector2d::Zero());
}

TEST(BiasAugmentedEkf, AHiddenRangeBiasIsFoundAndThePoseStaysOnTrack) {
  // The bias starts at +0.25 m and wanders with σ 0.15 m: the filter is told σ 0.15 m, τ 20 s.
  const auto run = circle_run(0.15, 0.25, 2);
  MotionModelEkf plain(kWheelbase, Pose2(0.0, -1.5, 0.0), kStart);
  MeasurementBiasModel model;
  model.range = {0.15, 20.0};
  model.bearing = {1e-4, 20.0};
  BiasAugmentedEkf augmented(kWheelbase, Pose2(0.0, -1.5, 0.0), kStart, model);
  double plain_sq = 0.0, augmented_sq = 0.0;
  int gated = 0, n = 0;
  for (const Step& s : run) {
    plain.predict(s.u, kBody);
    augmented.predict(s.u, kBody, 0.1);
    for (const auto& z : s.seen) {
      plain.update(z);
      gated += augmented.update(z, 13.8).gated ? 1 : 0;
      ++n;
    }
    plain_sq += std::pow(std::hypot(plain.mean()(0) - s.truth.x, plain.mean()(1) - s.truth.y), 2);
    augmented_sq += std::pow(std::hypot(augmented.mean()(0) - s.truth.x, augmented.mean()(1) - s.truth.y), 2);
  }
  const double plain_rmse = std::sqrt(plain_sq / run.size()), augmented_rmse = std::sqrt(augmented_sq / run.size());
  EXPECT_LT(augmented_rmse, 0.5 * plain_rmse) << "plain " << plain_rmse << " m, augmented " << augmented_rmse << " m";
  EXPECT_LT(augmented_rmse, 0.05);
  EXPECT_LE(gated, n / 50);
  // The last frame's bias, seen by the filter: within 5 cm of the bias drawn in the observations.
  const Step& last = run.back();
  double mean_residual = 0.0;
  for (const auto& z : last.seen)
    mean_residual += z.range - std::hypot(z.landmark_x - last.truth.x, z.landmark_y - last.truth.y);
  EXPECT_NEAR(augmented.bias()(0), mean_residual / 4.0, 0.05);
}

// Both filters updated with the four landmarks seen from `truth` (σ_r = 2 cm, σ_φ = 0.01 rad).
void observe_landmarks(const Pose2& truth, Rng& rng, MotionModelEkf& plain, BiasAugmentedEkf& augmented) {
  for (const auto& lm : kLandmarks) {
    const double dx = lm.x() - truth.x, dy = lm.y() - truth.y;
    const LandmarkRangeBearing z{std::hypot(dx, dy) + 0.02 * rng.normal(),
                                 wrap_angle(std::atan2(dy, dx) - truth.theta + 0.01 * rng.normal()),
                                 lm.x(),
                                 lm.y(),
                                 0.02 * 0.02,
                                 0.01 * 0.01};
    plain.update(z);
    augmented.update(z);
  }
}

// The mean NEES of the plain and the augmented filter over 20 seeds of `run`.
template <class Run>
std::pair<double, double> mean_over_seeds(Run run) {
  double plain = 0.0, augmented = 0.0;
  const int seeds = 20;
  for (int seed = 1; seed <= seeds; ++seed) {
    const auto [p, a] = run(static_cast<std::uint64_t>(seed));
    plain += p / seeds;
    augmented += a / seeds;
  }
  return {plain, augmented};
}

// 300 s on the circle with a motion error in the robot frame per 1 s window of σ 1 cm along,
// 0.5 cm left and 0.01 rad in heading, of which the share s = 0.8 is a Gauss–Markov process of
// τ = 10 s (the rest white); the four landmarks are seen every second for 10 s out of every 30 s.
// Returns the mean NEES over all steps of the plain filter (white noise of the same 1 s
// variance) and of the augmented one told s and τ.
std::pair<double, double> mean_nees_across_gaps(std::uint64_t seed) {
  Rng rng(seed);
  const double dt = 0.1, share = 0.8, tau = 10.0, window = 1.0;
  const Vector3 per_window(0.01 * 0.01, 0.005 * 0.005, 0.01 * 0.01);
  const Matrix3 body = (per_window * dt / window).asDiagonal();
  MotionNoiseCorrelation correlation;
  correlation.share = Vector3::Constant(share);
  correlation.time_s = Vector3::Constant(tau);
  correlation.window_s = window;
  const Pose2 start(0.0, -1.5, 0.0);
  MotionModelEkf plain(kWheelbase, start, kStart);
  BiasAugmentedEkf augmented(kWheelbase, start, kStart, {}, correlation);
  Pose2 truth = start;
  Vector3 m(rng.normal(), rng.normal(), rng.normal());  // the persistent error, unit variance
  const double a = std::exp(-dt / tau);
  double plain_sum = 0.0, augmented_sum = 0.0;
  const int steps = 3000;
  for (int k = 1; k <= steps; ++k) {
    const double d = 0.2 * dt, th = 0.2 / 1.5 * dt;
    const WheelDisplacement u{d - 0.5 * kWheelbase * th, d + 0.5 * kWheelbase * th};
    Vector3 e;  // the step's error in the robot frame at its start
    for (int j = 0; j < 3; ++j) {
      e(j) = std::sqrt((1.0 - share) * body(j, j)) * rng.normal() + std::sqrt(share * body(j, j) * dt / window) * m(j);
      m(j) = a * m(j) + std::sqrt(1.0 - a * a) * rng.normal();
    }
    const double c = std::cos(truth.theta), sn = std::sin(truth.theta);
    truth = odometry_step(truth, u, kWheelbase);
    truth = Pose2(truth.x + c * e(0) - sn * e(1), truth.y + sn * e(0) + c * e(1), wrap_angle(truth.theta + e(2)));
    plain.predict(u, body);
    augmented.predict(u, body, dt);
    if (k % 10 == 0 && (k / 10) % 30 < 10) {
      observe_landmarks(truth, rng, plain, augmented);
    }
    plain_sum += pose_nees(truth, plain.mean(), plain.covariance());
    augmented_sum += pose_nees(truth, augmented.mean(), augmented.covariance());
  }
  return {plain_sum / steps, augmented_sum / steps};
}

TEST(BiasAugmentedEkf, ACorrelatedMotionErrorIsCoveredAcrossGapsInTheObservations) {
  const auto [plain, augmented] = mean_over_seeds(mean_nees_across_gaps);
  // The NEES of a consistent 3-dof estimate averages 3.
  EXPECT_GT(augmented, 2.4);
  EXPECT_LT(augmented, 3.6);
  EXPECT_GT(plain, 2.0 * augmented) << "plain " << plain << ", augmented " << augmented;
}

// 300 s on the circle, commanded at 0.2 m/s, with drive stalls: a two-state chain that holds the
// robot still a fraction π = 0.2 of the time, in episodes of correlation time τ = 3 s (the
// robot's translation stops; its turn goes on). Both filters predict the mean translation
// (1 − π)·D; the plain one adds the stalls' spread as white noise per step, π(1 − π)·D², the
// augmented one carries the loss as its stall state (σ = √(π(1 − π)), τ). The four landmarks are
// seen every second for 10 s out of every 15 s (over longer gaps the position error reaches the
// metre, where the EKF's linearization, not its noise model, decides). Returns the mean NEES over
// all steps of each.
std::pair<double, double> mean_nees_with_stalls(std::uint64_t seed) {
  Rng rng(seed);
  const double dt = 0.1, pi = 0.2, tau = 3.0;
  const double d = 0.2 * dt, th = 0.2 / 1.5 * dt;
  const Vector3 floor(1e-6, 1e-6, 1e-6);
  Matrix3 plain_body = floor.asDiagonal();
  plain_body(0, 0) += pi * (1.0 - pi) * d * d;
  MotionNoiseCorrelation correlation;
  correlation.stall = {std::sqrt(pi * (1.0 - pi)), tau};
  const Pose2 start(0.0, -1.5, 0.0);
  MotionModelEkf plain(kWheelbase, start, kStart);
  BiasAugmentedEkf augmented(kWheelbase, start, kStart, {}, correlation);
  Pose2 truth = start;
  bool stalled = rng.bernoulli(pi);
  const double enter = 1.0 - std::exp(-pi / tau * dt), leave = 1.0 - std::exp(-(1.0 - pi) / tau * dt);
  double plain_sum = 0.0, augmented_sum = 0.0;
  const int steps = 3000;
  for (int k = 1; k <= steps; ++k) {
    const double moved = stalled ? 0.0 : d;
    truth = odometry_step(truth, {moved - 0.5 * kWheelbase * th, moved + 0.5 * kWheelbase * th}, kWheelbase);
    stalled = rng.bernoulli(stalled ? 1.0 - leave : enter);
    const double mean = (1.0 - pi) * d;
    const WheelDisplacement u{mean - 0.5 * kWheelbase * th, mean + 0.5 * kWheelbase * th};
    plain.predict(u, plain_body);
    augmented.predict(u, Matrix3(floor.asDiagonal()), dt, d);
    if (k % 10 == 0 && (k / 10) % 15 < 10) {
      observe_landmarks(truth, rng, plain, augmented);
    }
    plain_sum += pose_nees(truth, plain.mean(), plain.covariance());
    augmented_sum += pose_nees(truth, augmented.mean(), augmented.covariance());
  }
  return {plain_sum / steps, augmented_sum / steps};
}

TEST(BiasAugmentedEkf, StallsThatLastSecondsAreCoveredByTheStallState) {
  const auto [plain, augmented] = mean_over_seeds(mean_nees_with_stalls);
  EXPECT_GT(augmented, 2.4);
  EXPECT_LT(augmented, 3.6);
  EXPECT_GT(plain, 2.0 * augmented) << "plain " << plain << ", augmented " << augmented;
}

TEST(BiasAugmentedEkf, RejectsAMotionShareOutsideItsRange) {
  MotionNoiseCorrelation bad;
  bad.share = Vector3(1.0, 0.0, 0.0);
  EXPECT_THROW(BiasAugmentedEkf(kWheelbase, Pose2(), kStart, {}, bad), UsageError);
  bad.share = Vector3(0.5, 0.0, 0.0);
  bad.time_s = Vector3(0.0, 1.0, 1.0);
  EXPECT_THROW(BiasAugmentedEkf(kWheelbase, Pose2(), kStart, {}, bad), UsageError);
}

TEST(BiasAugmentedEkf, RejectsABiasWithoutACorrelationTime) {
  MeasurementBiasModel bad;
  bad.range = {0.1, 0.0};
  EXPECT_THROW(BiasAugmentedEkf(kWheelbase, Pose2(), kStart, bad), UsageError);
  bad.range = {-0.1, 1.0};
  EXPECT_THROW(BiasAugmentedEkf(kWheelbase, Pose2(), kStart, bad), UsageError);
}

}  // namespace
}  // namespace locbench::filters
