// The shared models: odometry action model, likelihood field, KLD sample count, low-variance
// resampling.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "baselines/global/likelihood_field.h"
#include "baselines/global/monte_carlo_localization.h"
#include "baselines/global/odometry_motion_model.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"

namespace locbench::baselines::global {
namespace {

TEST(OdometryMotionModel, DeltaRoundTripsForwardAndBackward) {
  const Pose2 a{1.0, 2.0, 0.3};
  for (const Pose2& rel : {Pose2(0.5, 0.1, 0.2), Pose2(-0.4, 0.05, -0.1), Pose2(0.0, 0.0, 1.0)}) {
    const Pose2 b = a * rel;
    const OdometryDelta d = odometry_delta(a, b);
    const Pose2 c = apply_delta(a, d);
    EXPECT_NEAR(c.x, b.x, 1e-12);
    EXPECT_NEAR(c.y, b.y, 1e-12);
    EXPECT_NEAR(angle_diff(c.theta, b.theta), 0.0, 1e-12);
    EXPECT_LE(std::abs(d.rot1), kPi / 2.0 + 1e-12);
  }
  EXPECT_LT(odometry_delta(a, a * Pose2(-0.4, 0.0, 0.0)).trans, 0.0);  // backwards
}

TEST(OdometryMotionModel, SamplesHaveTheModelsSpread) {
  OdometryMotionOptions o;
  o.alpha3 = 0.04;  // σ_trans = 0.2·|δtrans| (+ floor)
  o.min_translation_sigma = 0.0;
  o.min_rotation_sigma = 0.0;
  o.alpha4 = 0.0;
  const OdometryDelta d{0.0, 1.0, 0.0};
  Rng rng(3);
  double sum = 0.0, sq = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Pose2 p = sample_motion(Pose2{}, d, o, rng);
    const double along = p.x;
    sum += along;
    sq += along * along;
  }
  const double mean = sum / n, sd = std::sqrt(sq / n - mean * mean);
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_NEAR(sd, 0.2, 0.01);  // σ_trans, with a small cos contribution of rot noise
}

TEST(LikelihoodField, DistancesMatchBruteForceWithinACell) {
  const LineMap room = sim::room_world();
  LikelihoodFieldOptions o;
  o.max_distance = 2.0;
  const LikelihoodField f(room, o);
  Rng rng(11);
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p{rng.uniform(-0.5, 8.5), rng.uniform(-0.5, 8.5)};
    double d = 1e9;
    for (const Segment& s : room.segments) d = std::min(d, distance_to_segment(s, p));
    worst = std::max(worst, std::abs(f.distance(p.x(), p.y()) - std::min(d, 2.0)));
  }
  // The grid stores the distance of the cell centre: off by at most half a cell diagonal.
  EXPECT_LE(worst, o.resolution * std::sqrt(0.5) + 1e-6);
  EXPECT_EQ(f.distance(100.0, 100.0), 2.0);
}

TEST(LikelihoodField, TruePoseOutscoresAShiftedOne) {
  const LineMap room = sim::room_world();
  const LikelihoodField f(room, {});
  Scan scan;
  scan.bearings = even_bearings(181, deg(-90.0), deg(90.0));
  scan.max_range = 8.0;
  const Pose2 truth{2.0, 1.0, deg(46.0)};
  for (double b : scan.bearings) {
    const auto hit = room.ray_cast(truth.translation(), truth.theta + b, 8.0);
    scan.ranges.push_back(hit ? hit->range : 8.0);
  }
  const auto ends = f.beam_endpoints(scan);
  EXPECT_EQ(ends.size(), 20u);
  const double at_truth = f.log_likelihood(truth, ends);
  EXPECT_GT(at_truth, f.log_likelihood(Pose2(2.3, 1.0, deg(46.0)), ends) + 5.0);
  EXPECT_GT(at_truth, f.log_likelihood(Pose2(2.0, 1.0, deg(56.0)), ends) + 5.0);
}

TEST(KldSampling, SampleCountIsTheChiSquareBoundOfFox2003) {
  // n = χ²_{k−1, 1−δ} / (2ε); Fox's formula is its Wilson–Hilferty approximation.
  const double eps = 0.05, delta = 0.01;
  const double z = boost::math::quantile(boost::math::normal(), 1.0 - delta);
  EXPECT_NEAR(z, 2.326, 1e-3);
  EXPECT_EQ(kld_sample_count(1, eps, z), 0u);
  for (std::size_t k : {2u, 5u, 10u, 50u, 100u, 500u, 2000u}) {
    const double chi = boost::math::quantile(boost::math::chi_squared(static_cast<double>(k - 1)), 1.0 - delta);
    const double exact = chi / (2.0 * eps);
    const double n = static_cast<double>(kld_sample_count(k, eps, z));
    EXPECT_NEAR(n, exact, std::max(2.0, 0.03 * exact)) << "k = " << k;
  }
  // Hand-computed: k = 100 → 99/0.1 · (1 − 0.0022447 + 0.0473779·2.326)³ = 1346.5 → 1347.
  EXPECT_EQ(kld_sample_count(100, 0.05, 2.326), 1347u);
  EXPECT_THROW(kld_sample_count(10, 0.0, z), UsageError);
}

TEST(LowVarianceResampling, EachParticleGetsFloorOrCeilOfItsShare) {
  const std::vector<double> w{0.05, 0.3, 0.0, 0.15, 0.5};
  Rng rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t m = 37;
    const auto idx = low_variance_resample(w, m, rng);
    ASSERT_EQ(idx.size(), m);
    std::vector<int> count(w.size(), 0);
    for (std::size_t i = 0; i < m; ++i) {
      ++count[idx[i]];
      if (i > 0) {
        EXPECT_LE(idx[i - 1], idx[i]);
      }
    }
    for (std::size_t i = 0; i < w.size(); ++i) {
      const double share = w[i] * static_cast<double>(m);
      EXPECT_GE(count[i], std::floor(share) - 1e-9) << i;
      EXPECT_LE(count[i], std::ceil(share) + 1e-9) << i;
    }
    EXPECT_EQ(count[2], 0);
  }
}

TEST(LowVarianceResampling, UniformWeightsKeepEveryParticleOnce) {
  Rng rng(9);
  const std::vector<double> w(100, 2.5);  // unnormalised
  const auto idx = low_variance_resample(w, 100, rng);
  for (std::size_t i = 0; i < 100; ++i) EXPECT_EQ(idx[i], i);
}

TEST(LowVarianceResampling, RejectsBadWeights) {
  Rng rng(1);
  EXPECT_THROW(low_variance_resample(std::vector<double>{0.0, 0.0}, 3, rng), UsageError);
  EXPECT_THROW(low_variance_resample(std::vector<double>{1.0, -1.0}, 3, rng), UsageError);
  EXPECT_THROW(low_variance_resample(std::vector<double>{1.0, NAN}, 3, rng), UsageError);
}

TEST(GlobalOptions, RejectBadValuesAndUnknownKeys) {
  MclOptions m;
  EXPECT_THROW(from_json(nlohmann::json{{"min_particles", 0}}, m), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"particles", 10}}, m), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"field", {{"sigma_hit", -1.0}}}}, m), UsageError);
  EXPECT_THROW(from_json(nlohmann::json{{"alpha_fast", 0.0001}}, m), UsageError);
  nlohmann::json j = MclOptions{};
  MclOptions back;
  from_json(j, back);
  EXPECT_EQ(back.max_particles, MclOptions{}.max_particles);
  EXPECT_THROW(LikelihoodField(LineMap{}, {}), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::global
