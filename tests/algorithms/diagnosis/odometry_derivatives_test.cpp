// The exact likelihood derivatives (odometry_derivatives.h) against the plain likelihood: equal
// values, a gradient equal to central differences of the likelihood and a Hessian equal to
// central differences of that gradient, at random points for the parameters of every odometry
// cause (with the noise floor σ) on each kind of odometry and reference; then a whole diagnosis
// with exact derivatives against one with central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/diagnosis.h"
#include "algorithms/diagnosis/odometry_derivatives.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "diagnosis_test_helpers.h"
#include "tests/test_data.h"

namespace locbench::diagnosis {
namespace {

using Field = double OdometryModel::*;
using Point = test_support::DerivativePoint<OdometryModel>;

double nll_at(const MotionData& d, OdometryModel m, const Point& p, std::size_t i, double delta) {
  m.*(p.fields[i]) += delta;
  return negative_log_likelihood(d, m, {});
}

void expect_exact_derivatives(const MotionData& d, const Point& p) {
  SCOPED_TRACE(p.what);
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  WindowCache cache(d);
  const auto value = negative_log_likelihood_derivatives(d, p.model, {}, p.fields, g, h, &cache);
  ASSERT_TRUE(value.has_value());
  const double plain = negative_log_likelihood(d, p.model, {});
  EXPECT_NEAR(*value, plain, 1e-11 * std::abs(plain));
  const std::size_t n = p.fields.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double hi = p.steps[i];
    const double fd = (nll_at(d, p.model, p, i, hi) - nll_at(d, p.model, p, i, -hi)) / (2.0 * hi);
    // Rounding of the differenced likelihood: ~1e-15·|f|/h.
    EXPECT_NEAR(g[i], fd, 1e-5 * std::abs(fd) + 1e-12 * std::abs(plain) / hi) << "gradient " << i;
    OdometryModel up = p.model, down = p.model;
    up.*(p.fields[i]) += hi;
    down.*(p.fields[i]) -= hi;
    Eigen::VectorXd gu, gd;
    Eigen::MatrixXd unused;
    ASSERT_TRUE(negative_log_likelihood_derivatives(d, up, {}, p.fields, gu, unused).has_value());
    ASSERT_TRUE(negative_log_likelihood_derivatives(d, down, {}, p.fields, gd, unused).has_value());
    for (std::size_t j = 0; j < n; ++j) {
      const double fdh = (gu[j] - gd[j]) / (2.0 * hi);
      const double size = std::sqrt(std::abs(h(i, i) * h(j, j)));
      EXPECT_NEAR(h(i, j), fdh, 1e-5 * size + 1e-5 * std::abs(fdh)) << "Hessian " << i << "," << j;
    }
  }
}

// The noise floor and the cause's parameters at a random point near the cause's initial values.
Point random_point(const MotionData& d, const CauseSpec& c, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Point p;
  p.what = std::string(c.id);
  p.model.sigma_x = 0.01 * std::exp(u(rng));
  p.model.sigma_y = 0.01 * std::exp(u(rng));
  p.model.sigma_theta = 0.01 * std::exp(u(rng));
  if (d.reference != ReferenceKind::kCompass) {
    p.fields = {&OdometryModel::sigma_x, &OdometryModel::sigma_y};
    p.steps = {1e-7, 1e-7};
  }
  p.fields.push_back(&OdometryModel::sigma_theta);
  p.steps.push_back(1e-7);
  for (const auto& q : c.params) {
    double& v = p.model.*(q.field);
    v = q.positive ? q.initial * std::exp(u(rng)) : q.initial + 10.0 * q.scale * u(rng);
    if (std::find(p.fields.begin(), p.fields.end(), q.field) != p.fields.end()) continue;
    p.fields.push_back(q.field);
    p.steps.push_back(1e-5 * (q.positive ? v : q.scale));
    p.what += " " + q.name + "=" + std::to_string(v);
  }
  return p;
}

MotionData generated(sim::GeneratedReference reference, bool velocity, std::uint64_t seed) {
  sim::GeneratorOptions o;
  o.reference = reference;
  o.velocity_odometry = velocity;
  o.waypoints = 6;
  return build_motion_data(sim::generate_log({}, seed, o).log);
}

TEST(OdometryDerivatives, EqualCentralDifferencesForEveryCauseOnEveryKindOfLog) {
  std::mt19937_64 rng(27);
  for (const bool velocity : {false, true}) {
    for (const auto reference :
         {sim::GeneratedReference::kTruePose, sim::GeneratedReference::kRelations, sim::GeneratedReference::kCompass}) {
      const MotionData d = generated(reference, velocity, 5);
      for (const CauseSpec* c : odometry_causes(d)) {
        if (c->id == cause::kTimeOffset) continue;
        for (int k = 0; k < 2; ++k) expect_exact_derivatives(d, random_point(d, *c, rng));
      }
    }
  }
}

TEST(OdometryDerivatives, DeclineTheTimeOffsetWhichIsProfiled) {
  const MotionData d = generated(sim::GeneratedReference::kTruePose, false, 5);
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  EXPECT_FALSE(negative_log_likelihood_derivatives(d, {}, {}, {&OdometryModel::time_offset}, g, h).has_value());
}

TEST(OdometryDerivatives, EqualCentralDifferencesOnTheIntelLogsFittedModel) {
  LOCBENCH_REQUIRE_DATA("slam_benchmark");
  const MotionData d =
      build_motion_data(catalog::load_catalog_dataset(*catalog::find_dataset("intel"), catalog::data_root()));
  Point p;
  p.what = "intel";
  p.model.sigma_x = 0.0123;
  p.model.sigma_y = 0.0087;
  p.model.sigma_theta = 0.0061;
  p.model.stall_rate = 0.1438;
  p.model.stall_duration = 0.4476;
  p.model.turn_rate_scale = 0.9562;
  p.model.dof = 1.5045;
  p.fields = {&OdometryModel::sigma_x,    &OdometryModel::sigma_y,        &OdometryModel::sigma_theta,
              &OdometryModel::stall_rate, &OdometryModel::stall_duration, &OdometryModel::turn_rate_scale,
              &OdometryModel::dof};
  p.steps = {1e-7, 1e-7, 1e-7, 1e-6, 1e-6, 1e-7, 1e-5};
  expect_exact_derivatives(d, p);
}

// A whole diagnosis with exact derivatives and with central differences: the same causes, and
// every detected cause's estimates equal to 1e-4 of their interval's width and interval ends to
// 1% of it. The central-difference Hessian has rounding noise (steps of 1e-4·scale: 1e-7 for a
// scale, 1e-8 for a turn-rate bias) that moves interval ends by up to a few percent; a candidate
// that was not detected can be far worse (a flat or near-singular likelihood: a slip rate
// → ∞, dof → its bound, a speed-dependent scale correlated ≥ 0.99 with its slope), so only the
// detected causes are compared.
void expect_same_diagnosis(const Log& log) {
  DiagnosisOptions exact, differences;
  differences.exact_derivatives = false;
  const Diagnosis a = diagnose_log(log, exact), b = diagnose_log(log, differences);
  EXPECT_EQ(a.detected, b.detected);
  ASSERT_EQ(a.causes.size(), b.causes.size());
  for (std::size_t i = 0; i < a.causes.size(); ++i) {
    const Cause &x = a.causes[i], &y = b.causes[i];
    SCOPED_TRACE(x.id);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.detected, y.detected);
    if (!x.detected) continue;
    ASSERT_EQ(x.parameters.size(), y.parameters.size());
    for (std::size_t k = 0; k < x.parameters.size(); ++k) {
      const Estimate &p = x.parameters[k], &q = y.parameters[k];
      const double width = std::isfinite(q.hi - q.lo) ? std::abs(q.hi - q.lo) : 0.0;
      EXPECT_NEAR(p.value, q.value, 1e-4 * width + 1e-9 * std::abs(q.value)) << p.name;
      if (!std::isfinite(p.lo - q.lo) || !std::isfinite(p.hi - q.hi)) continue;
      EXPECT_NEAR(p.lo, q.lo, 0.01 * width + 1e-12) << p.name;
      EXPECT_NEAR(p.hi, q.hi, 0.01 * width + 1e-12) << p.name;
    }
  }
}

TEST(OdometryDerivatives, GiveTheDiagnosisOfCentralDifferencesOnLogsWithHiddenEffects) {
  sim::GeneratorOptions encoder;
  encoder.waypoints = 8;
  expect_same_diagnosis(sim::generate_log({{"wheel_diameter_ratio", 0.004}, {"wheel_slip", 0.3}}, 41, encoder).log);
  sim::GeneratorOptions velocity = encoder;
  velocity.velocity_odometry = true;
  expect_same_diagnosis(sim::generate_log({{"velocity_scale", -0.03}, {"turn_rate_bias", 0.01}}, 42, velocity).log);
}

}  // namespace
}  // namespace locbench::diagnosis
