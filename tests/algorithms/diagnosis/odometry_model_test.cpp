// The odometry model's parts checked against independent computations: the drive response
// against a fine Euler integration, the Student-t density against its normalisation and its
// normal limit, the window prediction against the scales it is given.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {
namespace {

// Velocity odometry: `n` steps of 0.1 s, the logged speed `v(i)` and turn rate 0.
MotionData straight_steps(std::size_t n, double (*v)(std::size_t)) {
  MotionData d;
  d.odometry = OdometryKind::kPose;
  d.reference = ReferenceKind::kRelations;
  for (std::size_t i = 0; i < n; ++i) {
    const double t0 = 0.1 * static_cast<double>(i);
    d.steps.push_back({t0, t0 + 0.1, v(i) * 0.1, 0.0});
  }
  return d;
}

// One second of velocity odometry at a constant 0.4 m/s.
MotionData one_second_at_0_4_m_per_s() {
  return straight_steps(10, [](std::size_t) { return 0.4; });
}

// The window over steps [first, last), its logged end at `t1` (0: its times left unset).
MotionWindow window_over(std::size_t first, std::size_t last, double t1 = 0.0) {
  MotionWindow w;
  w.first = first;
  w.last = last;
  w.t1 = t1;
  return w;
}

TEST(OdometryModel, TheDriveResponseMovesAsAFineEulerIntegrationOfTheFirstOrderLag) {
  // The logged speed jumps from 0 to 0.5 m/s at step 20; τ = 0.3 s.
  const MotionData d = straight_steps(40, [](std::size_t i) { return i < 20 ? 0.0 : 0.5; });
  const MotionWindow w = window_over(20, 30);  // the first second after the jump
  OdometryModel m;
  m.drive_tau = 0.3;
  const Pose2 p = predict_window(d, w, m);
  double u = 0.0, x = 0.0;
  for (int k = 0; k < 100000; ++k) {
    u += (0.5 - u) * 1e-5 / 0.3;
    x += u * 1e-5;
  }
  EXPECT_NEAR(p.x, x, 1e-5);  // Euler at 10 µs is good to ~5 µm; 0.5·(1 − 0.3·(1 − e^(−1/0.3))) = 0.3554 m
  EXPECT_NEAR(p.x, 0.5 * (1.0 - 0.3 * (1.0 - std::exp(-1.0 / 0.3))), 1e-9);
}

TEST(OdometryModel, TheDrivePredictionIsContinuousInTauWhereItsRunInCrossesAStep) {
  // Steps of 0.125 s (exact in binary, so they are contiguous) whose speed alternates 0.2 / 0.6 m/s;
  // at τ = 0.25 s the run-in's start, 4τ = 1 s before the window, falls on a step boundary. A
  // run-in that started there at that step's own speed jumped by ~e^−4·0.4·τ·(1 − e^(−Δt/τ)) ≈ 1.4 mm.
  MotionData d;
  d.odometry = OdometryKind::kPose;
  d.reference = ReferenceKind::kRelations;
  for (int i = 0; i < 40; ++i) {
    const double v = i % 2 == 0 ? 0.2 : 0.6;
    d.steps.push_back({0.125 * i, 0.125 * (i + 1), v * 0.125, 0.0});
  }
  const MotionWindow w = window_over(20, 28, 3.5);
  OdometryModel below, above;
  below.drive_tau = 0.25 - 1e-9;
  above.drive_tau = 0.25 + 1e-9;
  EXPECT_EQ(drive_run_in(d, w, 0.25).step, 12u);
  EXPECT_NEAR(predict_window(d, w, below).x, predict_window(d, w, above).x, 1e-9);
  // And it still responds to τ: 10 ms more lag moves the window's end by a measurable amount.
  OdometryModel later = above;
  later.drive_tau = 0.26;
  EXPECT_GT(std::abs(predict_window(d, w, later).x - predict_window(d, w, above).x), 1e-5);
}

TEST(OdometryModel, ScalesActOnTheLoggedMotionAndTheSpeedSlopeOnItsSpeed) {
  const MotionData d = one_second_at_0_4_m_per_s();
  const MotionWindow w = window_over(0, 10);
  OdometryModel m;
  m.velocity_scale = 0.95;
  EXPECT_NEAR(predict_window(d, w, m).x, 0.95 * 0.4, 1e-12);
  m.speed_slope = -0.1;  // (0.95 − 0.1·0.4)·0.4
  EXPECT_NEAR(predict_window(d, w, m).x, (0.95 - 0.04) * 0.4, 1e-12);
}

TEST(OdometryModel, StallsShortenTheMeanPredictionByTheirExpectedLoss) {
  // 1 s at 0.4 m/s; stalls at 0.2/s of 0.5 s: p = 1 − e^(−0.2) = 0.1813, f = 0.5, mean 0.4·(1 − p·f).
  const MotionData d = one_second_at_0_4_m_per_s();
  const MotionWindow w = window_over(0, 10, 1.0);
  OdometryModel m;
  m.stall_rate = 0.2;
  m.stall_duration = 0.5;
  const double p = 1.0 - std::exp(-0.2);
  EXPECT_NEAR(expected_stall_loss(d, w, m), 0.5 * p, 1e-12);
  EXPECT_NEAR(predict_window(d, w, m).x, 0.4 * (1.0 - 0.5 * p), 1e-12);
  m.stall_duration = 3.0;  // longer than the window: the whole window is lost
  EXPECT_NEAR(expected_stall_loss(d, w, m), p, 1e-12);
}

TEST(OdometryModel, TheStallLikelihoodIsTheTwoComponentMixtureOfTheMovingPrediction) {
  MotionData d = one_second_at_0_4_m_per_s();
  MotionWindow w = window_over(0, 10, 1.0);
  w.reference = Pose2(0.25, 0.01, 0.02);  // a window that lost 0.15 m of 0.4
  d.windows = {w};
  OdometryModel m;
  m.sigma_x = m.sigma_y = 0.02;
  m.sigma_theta = 0.03;
  m.stall_rate = 0.2;
  m.stall_duration = 0.5;
  const double p = 1.0 - std::exp(-0.2), v = 0.02 * 0.02;
  auto normal = [](double r, double var) { return std::exp(-0.5 * r * r / var) / std::sqrt(2.0 * M_PI * var); };
  // Moving: residual x = 0.25 − 0.4; stalled (half the window): x = 0.25 − 0.2.
  const double along = (1.0 - p) * normal(0.25 - 0.4, v) + p * normal(0.25 - 0.2, v);
  const double expected = -std::log(along * normal(0.01, v) * normal(0.02, 0.03 * 0.03));
  EXPECT_NEAR(negative_log_likelihood(d, m, {}), expected, 1e-9);
}

TEST(OdometryModel, TheStudentTDensityIsNormalisedAndTendsToTheNormal) {
  for (double dof : {1.5, 3.0, 10.0}) {
    double mass = 0.0;
    for (double r = -2000.0; r <= 2000.0; r += 0.01) mass += std::exp(component_log_density(r, 4.0, dof)) * 0.01;
    EXPECT_NEAR(mass, 1.0, dof < 2.0 ? 2e-2 : 1e-3) << dof;
  }
  EXPECT_NEAR(component_log_density(1.3, 2.0, 1e7), component_log_density(1.3, 2.0, 0.0), 1e-6);
  // Heavier tails: at 5 scale units the t with 3 dof is far more likely than the normal.
  EXPECT_GT(component_log_density(5.0, 1.0, 3.0), component_log_density(5.0, 1.0, 0.0) + 5.0);
}

// A true-pose reference at 100 Hz along a 0.4 m/s arc and 1 s windows over it.
MotionData windows_on_a_true_pose_arc() {
  MotionData d = straight_steps(100, [](std::size_t) { return 0.4; });
  d.reference = ReferenceKind::kTruePose;
  for (int i = 0; i <= 1000; ++i) {
    const double t = 0.01 * i;
    d.truth.push_back({t, Pose2(0.4 * t, 0.05 * t * t, 0.1 * t)});
  }
  for (std::size_t k = 0; k + 10 <= 100; k += 5) {
    MotionWindow w = window_over(k, k + 10, 0.1 * static_cast<double>(k + 10));
    w.t0 = 0.1 * static_cast<double>(k);
    d.windows.push_back(w);
  }
  return d;
}

TEST(WindowCache, GivesEachWindowsReferenceAtTheOffsetAndSharesItWithItsCopies) {
  const MotionData d = windows_on_a_true_pose_arc();
  WindowCache cache(d);
  for (const double offset : {0.0, 0.237, -0.5, 2.0}) {
    OdometryModel m;
    m.time_offset = offset;
    const std::vector<std::optional<Pose2>> refs = cache.references(m);
    ASSERT_EQ(refs.size(), d.windows.size());
    std::size_t uncovered = 0;
    for (std::size_t i = 0; i < d.windows.size(); ++i) {
      const std::optional<Pose2> expected = reference_window(d, d.windows[i], m);
      ASSERT_EQ(refs[i].has_value(), expected.has_value()) << "window " << i << ", offset " << offset;
      if (!expected) {
        ++uncovered;
        continue;
      }
      EXPECT_EQ(refs[i]->x, expected->x);  // the same computation: equal to the last bit
      EXPECT_EQ(refs[i]->y, expected->y);
      EXPECT_EQ(refs[i]->theta, expected->theta);
    }
    // The truth is looked up at t − offset: 0.237 s and 2 s uncover the windows starting in the
    // log's first 0.237 s and 2 s; −0.5 s uncovers the last window (it ends at the truth's end).
    const std::size_t expected_uncovered = offset == 0.0 ? 0 : offset == 2.0 ? 4 : 1;
    EXPECT_EQ(uncovered, expected_uncovered) << "offset " << offset;
  }
  // A copy (a fit made side by side) is handed the very values its original computed.
  OdometryModel m;
  m.time_offset = 0.237;
  const std::vector<std::optional<Pose2>>* original = &cache.references(m);
  WindowCache copy = cache;
  EXPECT_EQ(&copy.references(m), original);
}

}  // namespace
}  // namespace locbench::diagnosis
