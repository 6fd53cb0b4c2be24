// build_motion_data and the reference interpolation, on a log whose motion is known exactly:
// a 60 s arc at 0.5 m/s and 0.2 rad/s, ODOM and TRUEPOS at 10 Hz.
#include "algorithms/diagnosis/motion_windows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/angle.h"
#include "core/errors.h"

namespace locbench::diagnosis {
namespace {

constexpr double kV = 0.5, kW = 0.2;  // [m/s], [rad/s]

Pose2 arc(double t) {
  const double th = kW * t;
  return {kV / kW * std::sin(th), kV / kW * (1.0 - std::cos(th)), th};
}

Log arc_log(double seconds = 60.0) {
  Log log;
  log.name = "arc";
  log.params["robot_wheelbase"] = "0.4";
  for (int k = 0; k <= static_cast<int>(seconds * 10.0); ++k) {
    const double t = 0.1 * k;
    log.odometry.push_back({t, arc(t), kV, kW});
    log.truth.push_back({t, arc(t), arc(t)});
  }
  return log;
}

TEST(MotionWindows, AnOdomAndTrueposLogIsCutIntoOneSecondWindowsOfTheArc) {
  const MotionData d = build_motion_data(arc_log());
  EXPECT_EQ(d.odometry, OdometryKind::kPose);
  EXPECT_EQ(d.reference, ReferenceKind::kTruePose);
  EXPECT_NEAR(d.reference_interval, 0.1, 1e-9);
  ASSERT_GE(d.windows.size(), 55u);
  ASSERT_LE(d.windows.size(), 61u);
  for (const auto& w : d.windows) {
    const double dt = w.t1 - w.t0;
    EXPECT_NEAR(dt, 1.0, 0.11);
    EXPECT_NEAR(w.distance, kV * dt, 1e-3) << "window at " << w.t0;
    EXPECT_NEAR(w.turn, kW * dt, 1e-9);
    EXPECT_NEAR(w.heading, kW * w.t0 - 2.0 * std::numbers::pi * std::round(kW * w.t0 / (2.0 * std::numbers::pi)), 1e-9);
  }
}

TEST(MotionWindows, TruthIsInterpolatedLinearlyAndOnlyInsideItsSpan) {
  const std::vector<TruePose> truth = {{0.0, {0.0, 0.0, 3.0}, {}}, {1.0, {2.0, -1.0, -3.0}, {}}};
  const auto mid = interpolate_truth(truth, 0.5);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->x, 1.0, 1e-12);
  EXPECT_NEAR(mid->y, -0.5, 1e-12);
  // 3 rad → −3 rad is 0.283 rad the short way, through π.
  EXPECT_NEAR(std::abs(mid->theta), std::numbers::pi, 1e-9);
  EXPECT_FALSE(interpolate_truth(truth, -0.01).has_value());
  EXPECT_FALSE(interpolate_truth(truth, 1.01).has_value());
}

// 400 random queries — three per reading as the compass likelihood asks, plus jumps back and
// beyond either end — on truth with repeated time stamps: the stepping interpolator gives
// interpolate_truth's values bit for bit.
TEST(MotionWindows, TheSteppingTruthInterpolatorEqualsInterpolateTruthBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TruePose> truth;
  double t = 0.0;
  for (int k = 0; k < 200; ++k) {
    if (u(rng) > 0.1) t += 0.01 + 0.1 * u(rng);  // one record in ten repeats the previous time
    truth.push_back({t, {u(rng), u(rng), 6.0 * u(rng) - 3.0}, {}});
  }
  TruthInterpolator cursor(truth);
  int inside = 0;
  for (int q = 0; q < 400; ++q) {
    const double c = q % 50 == 49 ? (u(rng) * 1.4 - 0.2) * t : q * t / 400.0 + 0.05 * (q % 3 - 1);
    const auto a = interpolate_truth(truth, c), b = cursor.at(c);
    ASSERT_EQ(a.has_value(), b.has_value()) << "t = " << c;
    if (!a) continue;
    ++inside;
    EXPECT_EQ(a->x, b->x) << "t = " << c;
    EXPECT_EQ(a->y, b->y) << "t = " << c;
    EXPECT_EQ(a->theta, b->theta) << "t = " << c;
  }
  EXPECT_GT(inside, 350);
  // A time stamp shared by two records gives the first of them, as lower_bound does.
  const auto repeated =
      std::adjacent_find(truth.begin(), truth.end(), [](const TruePose& a, const TruePose& b) { return a.t == b.t; });
  ASSERT_NE(repeated, truth.end());
  EXPECT_EQ(TruthInterpolator(truth).at(repeated->t)->x, interpolate_truth(truth, repeated->t)->x);
}

// interpolate_truth searches from where a steady rate puts t (galloping), not by bisection: on
// truth with repeated stamps, a burst of fast records and a 30 s gap (the rate guess far off), it
// finds the record std::lower_bound finds, so every value is the bisection's bit for bit.
TEST(MotionWindows, TheGuessedSearchFindsTheRecordTheBisectionFinds) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<TruePose> truth;
  double t = 0.0;
  for (int k = 0; k < 3000; ++k) {
    if (k == 1000) t += 30.0;                                 // a gap
    const double step = k > 2000 && k < 2500 ? 0.001 : 0.01;  // a burst
    if (u(rng) > 0.1) t += step * (0.5 + u(rng));             // one record in ten repeats the previous time
    truth.push_back({t, {u(rng), u(rng), 6.0 * u(rng) - 3.0}, {}});
  }
  const auto bisection = [&](double q) {
    const auto b = std::lower_bound(truth.begin(), truth.end(), q, [](const TruePose& p, double v) { return p.t < v; });
    if (b == truth.begin()) return b->pose;
    const auto a = b - 1;
    const double dt = b->t - a->t, f = dt > 0.0 ? (q - a->t) / dt : 0.0;
    return Pose2(a->pose.x + f * (b->pose.x - a->pose.x), a->pose.y + f * (b->pose.y - a->pose.y),
                 a->pose.theta + f * angle_diff(b->pose.theta, a->pose.theta));
  };
  std::vector<double> queries{truth.front().t, truth.back().t};
  for (const TruePose& p : truth) queries.push_back(p.t);  // every stamp, repeated ones too
  for (int q = 0; q < 5000; ++q) queries.push_back(truth.front().t + u(rng) * (t - truth.front().t));
  for (double q : queries) {
    const auto got = interpolate_truth(truth, q);
    ASSERT_TRUE(got.has_value()) << "t = " << q;
    const Pose2 want = bisection(q);
    ASSERT_EQ(got->x, want.x) << "t = " << q;
    ASSERT_EQ(got->y, want.y) << "t = " << q;
    ASSERT_EQ(got->theta, want.theta) << "t = " << q;
  }
}

TEST(MotionWindows, CompassIsInterpolatedAlongTheShorterArc) {
  const std::vector<CompassReading> compass = {{0.0, 3.1}, {1.0, -3.1}, {2.0, -2.9}};
  const auto a = interpolate_compass(compass, 0.5);
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(std::abs(*a), std::numbers::pi, 1e-9);
  const auto b = interpolate_compass(compass, 1.5);
  ASSERT_TRUE(b.has_value());
  EXPECT_NEAR(*b, -3.0, 1e-12);
  EXPECT_FALSE(interpolate_compass(compass, 2.5).has_value());
}

TEST(MotionWindows, TooShortALogNamesTheLogAndTheWindowsNeeded) {
  try {
    build_motion_data(arc_log(10.0));
    FAIL() << "a 10 s log made windows";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("arc"), std::string::npos) << e.what();
  }
}

TEST(MotionWindows, AGapLongerThanMaxGapEndsAWindow) {
  Log log = arc_log();
  // Remove 3 s of odometry in the middle: no window may span the hole.
  std::erase_if(log.odometry, [](const OdometryReading& o) { return o.t > 30.05 && o.t < 32.95; });
  const MotionData d = build_motion_data(log);
  for (const auto& w : d.windows) {
    EXPECT_FALSE(w.t0 < 30.05 && w.t1 > 32.95) << "window " << w.t0 << "–" << w.t1 << " spans the gap";
  }
}

// The data are judged before any fit. A robot that never moves leaves no test any
// power; truth on another scale than the odometry is not a reference.
TEST(MotionWindows, ARobotThatNeverMovesIsAnErrorNotAVerdict) {
  Log log = arc_log();
  for (auto& o : log.odometry) o.pose = {}, o.tv = 0.0, o.rv = 0.0;
  for (auto& p : log.truth) p.pose = {};
  try {
    build_motion_data(log);
    FAIL() << "a motionless log made windows";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("never moves"), std::string::npos) << e.what();
  }
}

TEST(MotionWindows, TruthOnAnotherScaleThanTheOdometryIsAnError) {
  Log log = arc_log();
  for (auto& p : log.truth) p.pose.x *= 1000.0, p.pose.y *= 1000.0;
  try {
    build_motion_data(log);
    FAIL() << "truth x1000 made windows";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("TRUEPOS travels"), std::string::npos) << e.what();
  }
  // ×50 (a scale error a diagnosis should find, not refuse) is accepted.
  log = arc_log();
  for (auto& p : log.truth) p.pose.x *= 50.0, p.pose.y *= 50.0;
  EXPECT_NO_THROW(build_motion_data(log));
}

}  // namespace
}  // namespace locbench::diagnosis
