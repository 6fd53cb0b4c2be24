// Every filter of chapter 4 takes the landmark range-bearing update through the same interface as
// the compass: on a simulated circle among four landmarks with biased, noisy odometry each one
// tracks the truth, where dead reckoning drifts away.
#include <gtest/gtest.h>

#include <cmath>
#include <variant>
#include <vector>

#include "algorithms/filters/compass_ekf.h"
#include "algorithms/filters/motion_model_ekf.h"
#include "baselines/filters/fixed_q_ekf.h"
#include "baselines/filters/sage_husa_aekf.h"
#include "baselines/filters/vb_akf.h"
#include "core/rng.h"

namespace locbench::baselines::filters {
namespace {

using locbench::filters::CompassEkf, locbench::filters::CompassEkfOptions, locbench::filters::MotionModelEkf;

constexpr double kWheelbase = 0.26;
const Eigen::Vector2d kLandmarks[] = {{3.0, 0.0}, {-3.0, 0.0}, {0.0, 3.0}, {0.0, -3.0}};

struct Sample {
  WheelDisplacement u;  // measured wheel travel (2% too long on the right wheel, noisy)
  Pose2 truth;          // after the step
  std::vector<LandmarkRangeBearing> seen;
};

// 60 s on a circle of radius 1.5 m at 0.2 m/s, 10 steps per second, an observation of each
// landmark every second with σ_r = 3 cm, σ_φ = 0.02 rad.
std::vector<Sample> circle_run(std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Sample> out;
  Pose2 truth(0.0, -1.5, 0.0);
  const double v = 0.2, w = v / 1.5, dt = 0.1;
  for (int k = 1; k <= 600; ++k) {
    const double d = v * dt, th = w * dt;
    const WheelDisplacement exact{d - 0.5 * kWheelbase * th, d + 0.5 * kWheelbase * th};
    truth = odometry_step(truth, exact, kWheelbase);
    Sample s;
    s.u = {exact.left + 0.002 * rng.normal(), 1.02 * exact.right + 0.002 * rng.normal()};
    s.truth = truth;
    if (k % 10 == 0) {
      for (const auto& m : kLandmarks) {
        const double dx = m.x() - truth.x, dy = m.y() - truth.y;
        s.seen.push_back({std::hypot(dx, dy) + 0.03 * rng.normal(),
                          wrap_angle(std::atan2(dy, dx) - truth.theta + 0.02 * rng.normal()), m.x(), m.y(), 0.03 * 0.03,
                          0.02 * 0.02});
      }
    }
    out.push_back(s);
  }
  return out;
}

// The final position error; every update goes through the χ²₂(0.999) gate, of which at most 2%
// may reject (a consistent filter rejects 0.1%).
template <typename Filter, typename Predict>
double final_error(Filter f, const std::vector<Sample>& run, Predict predict, bool use_landmarks) {
  int updates = 0, gated = 0;
  for (const Sample& s : run) {
    predict(f, s.u);
    if (!use_landmarks) continue;
    for (const auto& z : s.seen) {
      ++updates;
      gated += f.update(z, 13.8).gated ? 1 : 0;
    }
  }
  EXPECT_LE(gated, updates / 50);
  const Pose2& t = run.back().truth;
  return std::hypot(f.mean()(0) - t.x, f.mean()(1) - t.y);
}

TEST(LandmarkUpdate, EveryFilterTracksTheCircleWhereDeadReckoningDrifts) {
  const auto run = circle_run(11);
  const Pose2 start(0.0, -1.5, 0.0);
  FixedQEkfOptions fq;
  fq.process_noise = {4e-6, 4e-6, 2e-4};  // the wheels' 2 mm per step: 1.2e-4 rad² of heading
  fq.initial_covariance = {1e-4, 1e-4, 1e-4};
  const auto step = [](auto& f, const WheelDisplacement& u) { f.predict(u); };
  const double drift = final_error(FixedQEkf(fq, kWheelbase, start), run, step, false);
  EXPECT_GT(drift, 0.5);

  EXPECT_LT(final_error(FixedQEkf(fq, kWheelbase, start), run, step, true), 0.05);
  CompassEkfOptions ad;
  ad.noise.k_left = ad.noise.k_right = 0.01;  // with σ = 5 mm: 8e-4 rad² of heading per step
  ad.initial_covariance = {1e-4, 1e-4, 1e-4};
  EXPECT_LT(final_error(CompassEkf(ad, kWheelbase, start), run, step, true), 0.05);
  SageHusaOptions sh;
  sh.initial_process_noise = {4e-6, 4e-6, 2e-4};
  sh.initial_covariance = {1e-4, 1e-4, 1e-4};
  sh.forgetting = 0.99;
  EXPECT_LT(final_error(SageHusaAekf(sh, kWheelbase, start), run, step, true), 0.05);
  VbAkfOptions vb;
  vb.process_noise = {4e-6, 4e-6, 2e-4};
  vb.initial_covariance = {1e-4, 1e-4, 1e-4};
  EXPECT_LT(final_error(VbAkf(vb, kWheelbase, start), run, step, true), 0.05);
  const Matrix3 body = Vector3(4e-6, 4e-6, 2e-4).asDiagonal();
  EXPECT_LT(final_error(
                MotionModelEkf(kWheelbase, start, Matrix3::Identity() * 1e-4), run,
                [&](MotionModelEkf& f, const WheelDisplacement& u) { f.predict(u, body); }, true),
            0.05);
}

TEST(LandmarkUpdate, CompassThroughTheGenericUpdateEqualsTheCompassStep) {
  // step(u, heading) and predict(u) + update(CompassHeading) are the same computation.
  FixedQEkfOptions o;
  o.initial_covariance = {1e-4, 1e-4, 1e-4};
  FixedQEkf a(o, 0.2, Pose2()), b(o, 0.2, Pose2());
  for (int k = 0; k < 20; ++k) {
    const WheelDisplacement u{0.05, 0.052};
    const double heading = 0.01 * k;
    a.step(u, heading);
    b.predict(u);
    b.update(CompassHeading{heading, o.compass_variance});
    EXPECT_EQ(a.mean(), b.mean());
    EXPECT_EQ(a.covariance(), b.covariance());
  }
}

TEST(LandmarkUpdate, SageHusaKeepsSeparateNoiseStatisticsPerMeasurementKind) {
  SageHusaOptions o;
  o.initial_covariance = {1e-4, 1e-4, 1e-4};
  SageHusaAekf f(o, 0.26, Pose2());
  f.predict({0.02, 0.02});
  f.update(LandmarkRangeBearing{2.5, 0.0, 2.5, 0.0, 0.01, 0.001});
  // The compass statistics are untouched by a landmark update: R̂ of the compass still R̂(0).
  const SageHusaStep s = f.step({0.02, 0.02}, std::nullopt);
  EXPECT_DOUBLE_EQ(s.measurement_variance, o.initial_measurement_noise);
  EXPECT_EQ(f.updates(), 1);
}

}  // namespace
}  // namespace locbench::baselines::filters
