#include "baselines/global/grid_markov.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "core/errors.h"
#include "datasets/sim/worlds.h"
#include "tests/baselines/global/sim_drive.h"

namespace locbench::baselines::global {
namespace {

GridMarkovOptions coarse() {
  GridMarkovOptions o;
  o.cell_size = 0.25;
  o.angular_cell = deg(10.0);
  o.update_min_distance = 0.25;
  return o;
}

TEST(GridMarkov, GridSizeAndMemoryFollowTheCells) {
  const LineMap room = sim::room_world();
  const GridMarkov g(room, coarse());
  EXPECT_EQ(g.cells_x(), 32);
  EXPECT_EQ(g.cells_y(), 32);
  EXPECT_EQ(g.cells_theta(), 36);
  EXPECT_EQ(g.cell_count(), 32u * 32u * 36u);
  EXPECT_GE(g.memory_bytes(), 2u * g.cell_count() * sizeof(double));
  const double sum = std::accumulate(g.belief().begin(), g.belief().end(), 0.0);
  EXPECT_NEAR(sum, 1.0, 1e-9);
  // The slides' 15 cm × 15 cm × 1° in the 8 m room: 54 × 54 × 360 = 1 049 760 cells.
  GridMarkovOptions fine = coarse();
  fine.cell_size = 0.15;
  fine.angular_cell = deg(1.0);
  const GridMarkov f(room, fine);
  EXPECT_EQ(f.cell_count(), 54u * 54u * 360u);
  EXPECT_GE(f.memory_bytes(), 16u * 1049760u);
}

TEST(GridMarkov, ActionUpdateMovesTheMassByTheOdometry) {
  const LineMap room = sim::room_world();
  GridMarkovOptions o = coarse();
  o.motion.alpha1 = o.motion.alpha2 = o.motion.alpha3 = o.motion.alpha4 = 0.0;
  o.motion.min_translation_sigma = 0.01;
  o.motion.min_rotation_sigma = 0.001;
  GridMarkov g(room, o);
  g.init_pose(Pose2(2.1, 4.1, deg(5.0)));
  EXPECT_NEAR(g.mass_near(Pose2(2.125, 4.125, deg(5.0)), 0.01, 0.01), 1.0, 1e-12);
  g.action_update({0.0, 1.0, 0.0});
  EXPECT_NEAR(std::accumulate(g.belief().begin(), g.belief().end(), 0.0), 1.0, 1e-9);
  // One metre along +x (cos 5° · 1 m = 0.996 m): the mass is now around x = 3.12.
  EXPECT_GT(g.mass_near(Pose2(3.12, 4.21, deg(5.0)), 0.3, deg(11.0)), 0.9);
  EXPECT_LT(g.mass_near(Pose2(2.125, 4.125, deg(5.0)), 0.3, deg(11.0)), 0.01);
  const Pose2 e = g.estimate();
  EXPECT_NEAR(e.x, 2.125 + std::cos(deg(5.0)), 0.13);
  EXPECT_NEAR(e.y, 4.125 + std::sin(deg(5.0)), 0.13);
}
TEST(GridMarkov, ConvergesInTheSimulatedRoomFromAUniformBelief) {
  const LineMap room = sim::room_world();
  const auto steps = test::room_run(21);
  GridMarkov g(room, coarse());
  std::size_t converged_at = steps.size();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    g.update(steps[i].odometry, steps[i].scan);
    // Converged: within two cells (the grid cannot resolve less than about half a cell).
    const bool ok = test::position_error(g.estimate(), steps[i].truth) < 0.5;
    if (ok && converged_at == steps.size()) converged_at = i;
    if (!ok) converged_at = steps.size();
  }
  EXPECT_LT(converged_at, steps.size() / 2);
  const Pose2 est = g.estimate();
  EXPECT_LT(test::position_error(est, steps.back().truth), 0.3);
  EXPECT_LT(std::abs(angle_diff(est.theta, steps.back().truth.theta)), deg(10.0));
  // The belief is concentrated: most of the mass within 0.5 m and 15° of the truth.
  EXPECT_GT(g.mass_near(steps.back().truth, 0.5, deg(15.0)), 0.8);
  EXPECT_GT(g.updates(), 20u);
}

TEST(GridMarkov, RejectsBadInput) {
  const LineMap room = sim::room_world();
  GridMarkovOptions o = coarse();
  o.cell_size = 0.0;
  EXPECT_THROW(GridMarkov(room, o), UsageError);
  o = coarse();
  o.cell_size = 0.01;
  o.angular_cell = deg(0.1);
  o.max_cells = 1e6;
  EXPECT_THROW(GridMarkov(room, o), UsageError);  // 800 × 800 × 3600 cells
  EXPECT_THROW(GridMarkov(LineMap{}, coarse()), UsageError);
  GridMarkovOptions back;
  EXPECT_THROW(from_json(nlohmann::json{{"cell", 0.1}}, back), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::global
