#include "baselines/global/monte_carlo_localization.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "datasets/sim/worlds.h"
#include "tests/baselines/global/sim_drive.h"

namespace locbench::baselines::global {
namespace {

struct RunStats {
  double final_position_error = 0.0;
  double final_heading_error = 0.0;
  std::size_t particles_at_end = 0;
  std::size_t first_converged = 0;  // step index after which the error stays < 0.3 m
  bool converged = false;
};

RunStats run(MonteCarloLocalization& mcl, const std::vector<test::Step>& steps, std::size_t from = 0) {
  RunStats s;
  for (std::size_t i = from; i < steps.size(); ++i) {
    mcl.update(steps[i].odometry, steps[i].scan);
    const double e = test::position_error(mcl.estimate(), steps[i].truth);
    if (e >= 0.3) {
      s.converged = false;
    } else if (!s.converged) {
      s.converged = true;
      s.first_converged = i;
    }
  }
  s.final_position_error = test::position_error(mcl.estimate(), steps.back().truth);
  s.final_heading_error = std::abs(angle_diff(mcl.estimate().theta, steps.back().truth.theta));
  s.particles_at_end = mcl.particle_count();
  return s;
}

TEST(MonteCarloLocalization, GlobalLocalizationInTheRoomFromAnUnknownStart) {
  const LineMap room = sim::room_world();
  const auto steps = test::room_run(21);
  ASSERT_GT(steps.size(), 200u);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    MonteCarloLocalization mcl(room, {}, seed);
    EXPECT_EQ(mcl.particle_count(), 5000u);
    const RunStats s = run(mcl, steps);
    EXPECT_TRUE(s.converged) << "seed " << seed;
    EXPECT_LT(s.final_position_error, 0.15) << "seed " << seed;
    EXPECT_LT(s.final_heading_error, 0.08) << "seed " << seed;
    // KLD-sampling shrank the set once the belief was unimodal.
    EXPECT_LT(s.particles_at_end, 1500u) << "seed " << seed;
    EXPECT_GE(s.particles_at_end, 100u);
    // Converged within the first half of the run.
    EXPECT_LT(s.first_converged, steps.size() / 2) << "seed " << seed;
  }
}

TEST(MonteCarloLocalization, FixedSampleCountWithoutKld) {
  const LineMap room = sim::room_world();
  const auto steps = test::room_run(21);
  MclOptions o;
  o.kld = false;
  o.max_particles = o.initial_particles = 5000;
  MonteCarloLocalization mcl(room, o, 4);
  const RunStats s = run(mcl, steps);
  EXPECT_EQ(s.particles_at_end, 5000u);
  EXPECT_LT(s.final_position_error, 0.15);
}

TEST(MonteCarloLocalization, RecoversFromAKidnappingOnlyWithRandomParticles) {
  const LineMap room = sim::room_world();
  const auto a = test::room_run(31);
  const auto steps = test::kidnapped(a, test::room_run_b(32));
  const std::size_t kidnap = a.size();
  for (bool inject : {true, false}) {
    MclOptions o;
    o.inject = inject;
    MonteCarloLocalization mcl(room, o, 7);
    const RunStats before = run(mcl, a);
    ASSERT_LT(before.final_position_error, 0.15) << "inject " << inject;
    const RunStats after = run(mcl, steps, kidnap);
    if (inject) {
      EXPECT_TRUE(after.converged);
      EXPECT_LT(after.final_position_error, 0.2);
    } else {
      // Carried 5.9 m away; without injection every particle stays near the old pose.
      EXPECT_GT(after.final_position_error, 1.0);
    }
  }
}

TEST(MonteCarloLocalization, TrackingFromAKnownPoseStaysClose) {
  const LineMap room = sim::room_world();
  const auto steps = test::room_run(41);
  MonteCarloLocalization mcl(room, {}, 5);
  mcl.init_pose(steps.front().truth, 0.05, 0.02);
  double worst = 0.0;
  for (const auto& s : steps) {
    mcl.update(s.odometry, s.scan);
    worst = std::max(worst, test::position_error(mcl.estimate(), s.truth));
  }
  EXPECT_LT(worst, 0.2);
}

TEST(MonteCarloLocalization, RejectsBadOptions) {
  const LineMap room = sim::room_world();
  MclOptions o;
  o.max_particles = 10;
  o.min_particles = 100;
  EXPECT_THROW(MonteCarloLocalization(room, o, 1), UsageError);
  EXPECT_THROW(MonteCarloLocalization(LineMap{}, MclOptions{}, 1), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::global
