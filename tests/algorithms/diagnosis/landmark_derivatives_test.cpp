// The exact landmark-likelihood derivatives (landmark_derivatives.h) against the plain likelihood:
// equal values, a gradient equal to central differences of the likelihood and a Hessian equal to
// central differences of that gradient, for the parameters of every landmark cause, on a simulated_landmarks
// landmark log; then the landmark channel with exact derivatives against central differences.
#include "algorithms/diagnosis/landmark_derivatives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "algorithms/diagnosis/landmark_channel.h"
#include "datasets/diagnosis/landmark_effects.h"
#include "diagnosis_test_helpers.h"

namespace locbench::diagnosis {
namespace {

using LmField = double LandmarkModel::*;

using LmPoint = test_support::DerivativePoint<LandmarkModel>;

LandmarkData simulated_landmarks(const std::vector<sim::HiddenEffect>& effects, double duration) {
  sim::LandmarkLogOptions o;
  o.duration = duration;
  const Log log = sim::generate_landmark_log(effects, 7, o).log;
  return make_landmark_data(log.landmarks, log.landmark_map, log.truth);
}

LandmarkModel with_step(LandmarkModel m, LmField f, double delta) {
  m.*f += delta;
  return m;
}

void expect_exact_landmark_derivatives(const LandmarkData& d, const LmPoint& p) {
  SCOPED_TRACE(p.what);
  const auto geometry = landmark_geometry(d, p.model.time_offset);
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  const auto value = landmark_nll_derivatives(d, geometry, p.model, {}, p.fields, g, h);
  ASSERT_TRUE(value.has_value());
  const double plain = landmark_nll(d, geometry, p.model, {});
  EXPECT_NEAR(*value, plain, 1e-11 * std::abs(plain));
  for (std::size_t i = 0; i < p.fields.size(); ++i) {
    const double step = p.steps[i];
    const LandmarkModel up = with_step(p.model, p.fields[i], step), down = with_step(p.model, p.fields[i], -step);
    const double fd = (landmark_nll(d, geometry, up, {}) - landmark_nll(d, geometry, down, {})) / (2.0 * step);
    EXPECT_NEAR(g[i], fd, 1e-5 * std::abs(fd) + 1e-12 * std::abs(plain) / step) << "gradient " << i;
    Eigen::VectorXd gu, gd;
    Eigen::MatrixXd unused;
    ASSERT_TRUE(landmark_nll_derivatives(d, geometry, up, {}, p.fields, gu, unused).has_value());
    ASSERT_TRUE(landmark_nll_derivatives(d, geometry, down, {}, p.fields, gd, unused).has_value());
    for (std::size_t j = 0; j < p.fields.size(); ++j) {
      const double fdh = (gu[j] - gd[j]) / (2.0 * step);
      const double size = std::sqrt(std::abs(h(i, i) * h(j, j)));
      EXPECT_NEAR(h(i, j), fdh, 1e-5 * size + 1e-5 * std::abs(fdh)) << "Hessian " << i << "," << j;
    }
  }
}

// σ_r and σ_b with the given fields, at random values near a camera's (scales near 1, biases of a
// few cm and mrad, a few degrees of freedom).
LmPoint random_landmark_point(const LandmarkData& d, const std::vector<LmField>& extra, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  LmPoint p;
  LandmarkModel& m = p.model;
  m.field_of_view = 0.4;  // some observations beyond it: s(φ) held there
  p.fields = {&LandmarkModel::sigma_range, &LandmarkModel::sigma_bearing};
  m.sigma_range = 0.03 * std::exp(0.5 * u(rng));
  m.sigma_bearing = 0.01 * std::exp(0.5 * u(rng));
  for (LmField f : extra) {
    p.fields.push_back(f);
    if (f == &LandmarkModel::range_scale) m.range_scale = 1.0 + 0.02 * u(rng);
    if (f == &LandmarkModel::dof) m.dof = 4.0 * std::exp(u(rng));
    if (f == &LandmarkModel::range_noise_slope || f == &LandmarkModel::bearing_noise_turn_slope) {
      m.*f = 0.01 * (1.5 + u(rng));
    }
    if (f != &LandmarkModel::range_scale && f != &LandmarkModel::dof && m.*f == 0.0) m.*f = 0.05 * u(rng);
  }
  if (std::find(extra.begin(), extra.end(), &LandmarkModel::position_error_dx) != extra.end()) {
    m.position_error_id = d.map[3].id;
  }
  for (LmField f : p.fields) {
    p.steps.push_back(1e-6);
    p.what += std::to_string(m.*f) + " ";
  }
  return p;
}

TEST(LandmarkDerivatives, EqualCentralDifferencesForEveryCausesParameters) {
  const LandmarkData d = simulated_landmarks({}, 120.0);
  std::mt19937_64 rng(31);
  const std::vector<std::vector<LmField>> sets = {
      {},
      {&LandmarkModel::range_scale, &LandmarkModel::range_bias, &LandmarkModel::bearing_bias},
      {&LandmarkModel::range_off_axis_linear, &LandmarkModel::range_off_axis},
      {&LandmarkModel::range_noise_slope, &LandmarkModel::bearing_noise_turn_slope},
      {&LandmarkModel::dof},
      {&LandmarkModel::position_error_dx, &LandmarkModel::position_error_dy},
      {&LandmarkModel::range_scale, &LandmarkModel::range_bias, &LandmarkModel::range_off_axis_linear,
       &LandmarkModel::range_off_axis, &LandmarkModel::bearing_bias, &LandmarkModel::range_noise_slope,
       &LandmarkModel::bearing_noise_turn_slope, &LandmarkModel::dof, &LandmarkModel::position_error_dx,
       &LandmarkModel::position_error_dy}};
  for (const auto& fields : sets) {
    for (int k = 0; k < 2; ++k) expect_exact_landmark_derivatives(d, random_landmark_point(d, fields, rng));
  }
}

TEST(LandmarkDerivatives, DeclineTheTimeOffsetWhichIsProfiled) {
  const LandmarkData d = simulated_landmarks({}, 60.0);
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  const LandmarkModel m;
  EXPECT_FALSE(
      landmark_nll_derivatives(d, landmark_geometry(d, 0.0), m, {}, {&LandmarkModel::time_offset}, g, h).has_value());
}

// σ_r at its boundary 0, the range noise all in the slope (MRCLAM's fits put it there): every
// covered reading's variance is (slope·ρ)² in the plain likelihood too, so the derivatives stay
// exact; without a slope the likelihood uses its floor on σ_r² and they are declined.
TEST(LandmarkDerivatives, StayExactWithSigmaRangeAtZeroWhenTheSlopeCarriesTheRangeNoise) {
  const LandmarkData d = simulated_landmarks({}, 60.0);
  LandmarkModel m;
  m.sigma_range = 1e-9;
  m.sigma_bearing = 0.01;
  m.range_noise_slope = 0.02;
  expect_exact_landmark_derivatives(
      d, {m,
          {&LandmarkModel::sigma_bearing, &LandmarkModel::range_noise_slope, &LandmarkModel::range_bias},
          {1e-6, 1e-6, 1e-6},
          "sigma_range 1e-9"});
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  const auto geometry = landmark_geometry(d, 0.0);
  EXPECT_TRUE(landmark_nll_derivatives(d, geometry, m, {}, {&LandmarkModel::sigma_range}, g, h).has_value());
  m.range_noise_slope = 0.0;
  EXPECT_FALSE(landmark_nll_derivatives(d, geometry, m, {}, {&LandmarkModel::sigma_range}, g, h).has_value());
}

// The channel with exact derivatives and with central differences: the same causes, and every
// detected cause's estimates equal to 1e-3 of their interval's width and interval ends to 1% of it
// (the central-difference Hessian has rounding noise of that order).
TEST(LandmarkDerivatives, GiveTheChannelOfCentralDifferencesOnALogWithHiddenEffects) {
  const LandmarkData d = simulated_landmarks({{"landmark_range_scale", 0.03}, {"landmark_bearing_bias", 0.02}}, 600.0);
  DiagnosisOptions exact, differences;
  differences.exact_derivatives = false;
  const LandmarkChannelResult a = diagnose_landmarks(d, exact), b = diagnose_landmarks(d, differences);
  ASSERT_EQ(a.causes.size(), b.causes.size());
  for (std::size_t i = 0; i < a.causes.size(); ++i) {
    const Cause &x = a.causes[i], &y = b.causes[i];
    SCOPED_TRACE(x.id);
    EXPECT_EQ(x.detected, y.detected);
    if (!x.detected) continue;
    ASSERT_EQ(x.parameters.size(), y.parameters.size());
    for (std::size_t k = 0; k < x.parameters.size(); ++k) {
      const Estimate &p = x.parameters[k], &q = y.parameters[k];
      const double width = std::abs(q.hi - q.lo);
      EXPECT_NEAR(p.value, q.value, 1e-3 * width + 1e-9 * std::abs(q.value)) << p.name;
      EXPECT_NEAR(p.lo, q.lo, 0.01 * width + 1e-12) << p.name;
      EXPECT_NEAR(p.hi, q.hi, 0.01 * width + 1e-12) << p.name;
    }
  }
}

}  // namespace
}  // namespace locbench::diagnosis
