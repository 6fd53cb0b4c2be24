#include "algorithms/pose_correction/ekf_tracker.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/worlds.h"
#include "tests/algorithms/pose_correction/ray_cast_matches.h"

namespace locbench::pose_correction {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

PoseCorrection heading_only(double delta, double variance) {
  PoseCorrection c;
  c.heading_fixed = true;
  c.delta = {0.0, 0.0, delta};
  c.covariance = Matrix3d::Zero();
  c.covariance(0, 0) = c.covariance(1, 1) = std::numeric_limits<double>::infinity();
  c.covariance(2, 2) = variance;
  return c;
}

PoseCorrection full(const Vector3d& delta, const Matrix3d& cov) {
  PoseCorrection c;
  c.heading_fixed = c.position_fixed = true;
  c.delta = delta;
  c.covariance = cov;
  return c;
}

EkfTrackerOptions with_p0(const Vector3d& p0) {
  EkfTrackerOptions o;
  o.initial_covariance = p0;
  return o;
}

TEST(EkfTracker, PredictionIsTheCoreOdometryStepAndCovariancePropagation) {
  EkfTrackerOptions o = with_p0({1e-4, 2e-4, 1e-3});
  const Pose2 start{1.0, 2.0, 0.3};
  EkfTracker t(o, 0.33, start);
  const WheelDisplacement u{0.039, 0.041};
  t.predict(u);
  const Pose2 expected = odometry_step(start, u, 0.33);
  EXPECT_NEAR(t.pose().x, expected.x, 1e-15);
  EXPECT_NEAR(t.pose().theta, expected.theta, 1e-15);
  const Matrix3d p = propagate_covariance(Vector3d(1e-4, 2e-4, 1e-3).asDiagonal(), start, u, 0.33, o.wheel_noise);
  EXPECT_TRUE(t.covariance().isApprox(p, 1e-12));
}

TEST(EkfTracker, HeadingOnlyCorrectionIsAScalarUpdateOnTheta) {
  // Eq. 6.42 with P = diag(0.01, 0.01, 0.01), Δθ = 0.1 rad with R = 0.01: the heading moves
  // halfway, its variance halves, x and y (uncorrelated) stay.
  EkfTracker t(with_p0({0.01, 0.01, 0.01}), 0.33, Pose2{1.0, 1.0, 0.0});
  const TrackerUpdate u = t.update(heading_only(0.1, 0.01));
  EXPECT_EQ(u.kind, TrackerUpdateKind::kHeading);
  EXPECT_EQ(u.dof, 1);
  EXPECT_NEAR(u.nis, 0.01 / 0.02, 1e-12);
  EXPECT_NEAR(t.pose().theta, 0.05, 1e-12);
  EXPECT_NEAR(t.pose().x, 1.0, 1e-15);
  EXPECT_NEAR(t.covariance()(2, 2), 0.005, 1e-12);
  EXPECT_NEAR(t.covariance()(0, 0), 0.01, 1e-15);
}

TEST(EkfTracker, HeadingOnlyCorrectionMovesPositionThroughItsCorrelationWithHeading) {
  // After driving, y and θ are correlated; a heading fix pulls y along (K = P H ᵀ/S).
  EkfTracker t(with_p0({0.0, 0.0, 0.01}), 0.33, Pose2{0.0, 0.0, 0.0});
  t.predict({1.0, 1.0});
  const double pyt = t.covariance()(1, 2), ptt = t.covariance()(2, 2);
  ASSERT_GT(pyt, 0.0);
  const double y0 = t.pose().y;
  t.update(heading_only(0.02, 0.0001));
  EXPECT_NEAR(t.pose().y - y0, pyt / (ptt + 0.0001) * 0.02, 1e-12);
}

TEST(EkfTracker, FullCorrectionWithEqualCovariancesMovesHalfway) {
  // Eq. 6.41: H = I; P = R ⇒ K = I/2.
  const Vector3d p0{0.04, 0.04, 0.01};
  EkfTracker t(with_p0(p0), 0.33, Pose2{2.0, 1.0, 0.5});
  const TrackerUpdate u = t.update(full({-0.2, 0.1, -0.1}, p0.asDiagonal()));
  EXPECT_EQ(u.kind, TrackerUpdateKind::kFull);
  EXPECT_EQ(u.dof, 3);
  EXPECT_NEAR(t.pose().x, 1.9, 1e-12);
  EXPECT_NEAR(t.pose().y, 1.05, 1e-12);
  EXPECT_NEAR(t.pose().theta, 0.45, 1e-12);
  EXPECT_TRUE(t.covariance().isApprox(Matrix3d(0.5 * p0.asDiagonal()), 1e-12));
  // NIS = νᵀ(2P)⁻¹ν.
  EXPECT_NEAR(u.nis, 0.04 / 0.08 + 0.01 / 0.08 + 0.01 / 0.02, 1e-12);
}

TEST(EkfTracker, NothingFixedMeansNoUpdate) {
  EkfTracker t(with_p0({0.01, 0.01, 0.01}), 0.33, Pose2{});
  const TrackerUpdate u = t.update(PoseCorrection{});
  EXPECT_EQ(u.kind, TrackerUpdateKind::kNone);
  EXPECT_EQ(t.covariance()(0, 0), 0.01);
}

TEST(EkfTracker, OptionalGateRejectsAnImplausibleCorrection) {
  EkfTrackerOptions o = with_p0({1e-4, 1e-4, 1e-4});
  o.gate_probability = 0.999;
  EkfTracker t(o, 0.33, Pose2{});
  // 1 m off with σ ≈ 14 mm: NIS ≈ 5000 ≫ χ²₃(0.999) = 16.3.
  const TrackerUpdate u = t.update(full({1.0, 0.0, 0.0}, Vector3d(1e-4, 1e-4, 1e-4).asDiagonal()));
  EXPECT_TRUE(u.gated_out);
  EXPECT_EQ(u.kind, TrackerUpdateKind::kNone);
  EXPECT_EQ(t.pose().x, 0.0);
  // A plausible one passes.
  EXPECT_EQ(t.update(full({0.01, 0.0, 0.0}, Vector3d(1e-4, 1e-4, 1e-4).asDiagonal())).kind, TrackerUpdateKind::kFull);
}

TEST(EkfTracker, RejectsInvalidConstruction) {
  EXPECT_THROW(EkfTracker({}, 0.0, Pose2{}), UsageError);
  EkfTrackerOptions o;
  o.gate_probability = 1.0;
  EXPECT_THROW(EkfTracker(o, 0.33, Pose2{}), UsageError);
  EXPECT_THROW((nlohmann::json{{"wheel_noise_k_left", -1.0}}.get<EkfTrackerOptions>()), UsageError);
  const nlohmann::json j = EkfTrackerOptions{};
  EXPECT_EQ(j.get<EkfTrackerOptions>().wheel_noise.k_left, EkfTrackerOptions{}.wheel_noise.k_left);
}

// A matcher stand-in that knows the true pose: assigns each beam to the segment it really hit.
class OracleMatcher : public laser::SegmentMatcher {
 public:
  explicit OracleMatcher(const test::RayCastScan& scan) : scan_(scan) {}
  std::string name() const override { return "oracle"; }
  laser::MatchResult match(const Scan&, const LineMap&, const Pose2& estimate) const override {
    return {test::matches_by_true_hit(scan_, estimate), 0};
  }

 private:
  const test::RayCastScan& scan_;
};

TEST(EkfTracker, CorrectsFromAScanThroughAMatcherAtThePredictedPose) {
  // §6.6.1's situation as one filter step: estimate (2.1, 1.1, 41°) with a prior that covers
  // its error, true pose (2.0, 1.0, 46°), one noisy scan of the room.
  const LineMap room = sim::room_world();
  const Pose2 truth{2.0, 1.0, deg(46.0)};
  EkfTracker t(with_p0({0.1 * 0.1, 0.1 * 0.1, std::pow(deg(5.0), 2)}), 0.33, Pose2{2.1, 1.1, deg(41.0)});
  Rng rng(13);
  const auto scan = test::ray_cast_scan(room, truth, &rng);
  const TrackerUpdate u = t.correct(scan.scan, room, OracleMatcher(scan));
  EXPECT_EQ(u.kind, TrackerUpdateKind::kFull);
  EXPECT_NEAR(u.innovation(2), deg(5.0), deg(0.2));
  EXPECT_LT(translation_distance(t.pose(), truth), mm(10.0));
  EXPECT_LT(std::abs(angle_diff(t.pose().theta, truth.theta)), deg(0.2));
  EXPECT_LT(t.covariance()(0, 0), 1e-4);
}

// §6.6.2 simulated: a Pioneer-like robot (nominal D = 193.5 mm both, B = 0.33 m; true D_L =
// 193.3, D_R = 193.7 mm, B = 0.332 m, floor noise 2 mm/√m per wheel) drives 10 m straight
// along the centre of a 12 × 1.8 m corridor from (1, 0, 0) at 200 mm/s; encoders and an
// LMS 200-like laser (σ = 5 mm) at 5 Hz. Matches come from the true hits (the matchers'
// stand-in). Until x ≈ 4 m the end wall is beyond 8 m: heading-only updates; then full ones.
struct CorridorRun {
  double odometry_error = 0.0;  // final position error of dead reckoning [m]
  double ekf_error = 0.0;       // final position error of the tracker [m] (eq. 6.43)
  std::vector<double> nees;     // after each update
  int heading_updates = 0;
  int full_updates = 0;
};

CorridorRun run_corridor(std::uint64_t seed) {
  const LineMap corridor = sim::corridor_world(12.0, 1.8);
  Rng floor(Rng::derive_seed(seed, 1)), laser(Rng::derive_seed(seed, 2));
  const double v_step = 0.2 / 5.0;  // 40 mm per 0.2 s
  const double k_floor = 0.002 * 0.002;
  Pose2 truth{1.0, 0.0, 0.0}, odometry = truth;
  EkfTracker ekf({}, 0.33, truth);
  CorridorRun out;
  for (int k = 0; k < 250; ++k) {
    const WheelDisplacement ground{v_step + floor.normal(0.0, std::sqrt(k_floor * v_step)),
                                   v_step + floor.normal(0.0, std::sqrt(k_floor * v_step))};
    truth = odometry_step(truth, ground, 0.332);
    const WheelDisplacement measured{v_step * 193.5 / 193.3, v_step * 193.5 / 193.7};
    odometry = odometry_step(odometry, measured, 0.33);
    ekf.predict(measured);
    const auto scan = test::ray_cast_scan(corridor, truth, &laser);
    const auto matches = test::matches_by_true_hit(scan, ekf.pose());
    const TrackerUpdate u = ekf.correct(matches, corridor, scan.scan.sensor_pose);
    if (u.kind == TrackerUpdateKind::kHeading) ++out.heading_updates;
    if (u.kind == TrackerUpdateKind::kFull) ++out.full_updates;
    const Vector3d e{truth.x - ekf.mean()(0), truth.y - ekf.mean()(1), angle_diff(truth.theta, ekf.mean()(2))};
    const Eigen::LLT<Matrix3d> llt(ekf.covariance());
    if (llt.info() == Eigen::Success) out.nees.push_back(e.dot(llt.solve(e)));
  }
  out.odometry_error = translation_distance(odometry, truth);
  out.ekf_error = translation_distance(ekf.pose(), truth);
  return out;
}

TEST(EkfTrackerCorridor, EndsCloserToTheTruthThanOdometryAndStaysConsistent) {
  const double chi2_999 = boost::math::quantile(boost::math::chi_squared(3.0), 0.999);
  double nees_sum = 0.0;
  std::size_t nees_n = 0, nees_high = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const CorridorRun r = run_corridor(seed);
    EXPECT_GT(r.heading_updates, 50) << seed;   // x < 4 m: side walls only
    EXPECT_GT(r.full_updates, 100) << seed;     // the end wall within 8 m
    EXPECT_GT(r.odometry_error, 0.05) << seed;  // 0.08–0.58 m over seeds 1–5
    EXPECT_LT(r.ekf_error, 0.2 * r.odometry_error) << seed;
    EXPECT_LT(r.ekf_error, mm(20.0)) << seed;
    for (const double n : r.nees) {
      nees_sum += n;
      ++nees_n;
      if (n > chi2_999) ++nees_high;
    }
  }
  // Not over-confident: the average NEES (expectation 3; measured 1.5–1.7, the 5 mm floor of R
  // makes it conservative) below 6, few steps beyond χ²₃(0.999). Steps whose P is still
  // singular (the first, from P(0) = 0) are skipped.
  const double mean_nees = nees_sum / static_cast<double>(nees_n);
  EXPECT_LT(mean_nees, 6.0);
  EXPECT_LT(static_cast<double>(nees_high) / static_cast<double>(nees_n), 0.05);
}

}  // namespace
}  // namespace locbench::pose_correction
