// The slides' worked example of Markov localization on a topological map (Dervish; seed slides
// /work/shared/seeds/003_203ac967e0c55a47.txt, "马尔可夫定位：实例研究 1 – 拓扑地图"):
// prior p(1-2) = 1.0, p(2-3) = 0.2, facing east; 1-2 moves to 2, 2-3 to 3, 3-4 or 4 (each with
// probability 1, not normalised); observation "open hallway on the left, open door on the
// right"; p(i|2) = 0.9 × (0.6 × 0 + 0.4 × 0.9) = 0.324, p(i|3) = p(i|3-4) = 0,
// p(i|4) = 0.9 × 0.1 = 0.09; posteriors 0.324 at node 2 and 0.018 at node 4: 18 : 1.
#include "baselines/global/topological_markov.h"

#include <gtest/gtest.h>

#include "core/errors.h"

namespace locbench::baselines::global {
namespace {

const SideModel kWall = {{Feature::kWall, 1.0}};
const SideModel kHallway = {{Feature::kOpenHallway, 1.0}};
// A door of unknown state: closed 0.6, open 0.4 (the slides' superscripts on the table).
const SideModel kDoor = {{Feature::kClosedDoor, 0.6}, {Feature::kOpenDoor, 0.4}};

// The corridor of the example as the slides' calculation needs it: at 2 an open hallway on the
// left and a door on the right; at 3 and 3-4 a wall on the right; at 4 open hallways on both
// sides. (Sides the slides do not state — left of 3 and 3-4, the edges 1-2 and 2-3 — are walls;
// they do not enter the result: 1-2 and 2-3 hold no mass after the action, and 3, 3-4 have
// p(open door | wall) = 0 on the right.)
std::vector<TopologicalNode> dervish_map() {
  return {{"1-2", kWall, kWall}, {"2", kHallway, kDoor}, {"2-3", kWall, kWall},
          {"3", kWall, kWall},   {"3-4", kWall, kWall},  {"4", kHallway, kHallway}};
}

// p(l | l', o_t) of the slides' step, rows l, columns l' (order 1-2, 2, 2-3, 3, 3-4, 4).
std::vector<std::vector<double>> dervish_transition() {
  std::vector<std::vector<double>> t(6, std::vector<double>(6, 0.0));
  t[1][0] = 1.0;  // p(2 | 1-2) = 1
  t[3][2] = 1.0;  // p(3 | 2-3) = 1
  t[4][2] = 1.0;  // p(3-4 | 2-3) = 1
  t[5][2] = 1.0;  // p(4 | 2-3) = 1
  return t;
}

const TopologicalObservation kObservation{Detection::kOpenHallway, Detection::kOpenDoor};

TEST(TopologicalMarkov, DervishTableIsTheSlides) {
  const SensorTable t = dervish_sensor_table();
  EXPECT_DOUBLE_EQ(t[0][0], 0.70);  // nothing detected | wall
  EXPECT_DOUBLE_EQ(t[0][3], 0.001);
  EXPECT_DOUBLE_EQ(t[1][1], 0.60);  // closed door detected | closed door
  EXPECT_DOUBLE_EQ(t[2][2], 0.90);  // open door detected | open door
  EXPECT_DOUBLE_EQ(t[2][3], 0.10);  // open door detected | open hallway
  EXPECT_DOUBLE_EQ(t[3][3], 0.90);  // open hallway detected | open hallway
  EXPECT_DOUBLE_EQ(t[3][4], 0.50);  // open hallway detected | foyer
}

TEST(TopologicalMarkov, ReproducesTheSlidesWorkedExample) {
  TopologicalMarkov m(dervish_map(), dervish_sensor_table());
  m.set_belief({1.0, 0.0, 0.2, 0.0, 0.0, 0.0});  // p(1-2) = 1.0, p(2-3) = 0.2 (5 : 1)
  m.action_update(dervish_transition());
  // p_t(2|o) = 1, p_t(2-3|o) = 0, p_t(3|o) = p_t(3-4|o) = p_t(4|o) = 0.2
  EXPECT_NEAR(m.belief()[m.index("2")], 1.0, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("2-3")], 0.0, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("3")], 0.2, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("3-4")], 0.2, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("4")], 0.2, 1e-12);

  EXPECT_NEAR(m.likelihood(m.index("2"), kObservation), 0.324, 1e-12);
  EXPECT_NEAR(m.likelihood(m.index("3"), kObservation), 0.0, 1e-12);
  EXPECT_NEAR(m.likelihood(m.index("3-4"), kObservation), 0.0, 1e-12);
  EXPECT_NEAR(m.likelihood(m.index("4"), kObservation), 0.09, 1e-12);

  m.perception_update(kObservation);
  const double at2 = m.belief()[m.index("2")], at4 = m.belief()[m.index("4")];
  EXPECT_NEAR(at2, 0.324, 1e-12);
  EXPECT_NEAR(at4, 0.018, 1e-12);
  EXPECT_NEAR(at2 / at4, 18.0, 1e-9);  // 18 : 1
  EXPECT_NEAR(m.belief()[m.index("3")], 0.0, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("3-4")], 0.0, 1e-12);
}

TEST(TopologicalMarkov, NormalisedVariantKeepsTheRatio) {
  TopologicalMarkov m(dervish_map(), dervish_sensor_table(), {.normalise = true});
  m.set_belief({1.0, 0.0, 0.2, 0.0, 0.0, 0.0});
  m.action_update(dervish_transition());
  m.perception_update(kObservation);
  EXPECT_NEAR(m.belief()[m.index("2")], 18.0 / 19.0, 1e-12);
  EXPECT_NEAR(m.belief()[m.index("4")], 1.0 / 19.0, 1e-12);
}

TEST(TopologicalMarkov, RejectsBadInput) {
  EXPECT_THROW(TopologicalMarkov({}, dervish_sensor_table()), UsageError);
  auto bad_side = dervish_map();
  bad_side[1].right = {{Feature::kClosedDoor, 0.6}, {Feature::kOpenDoor, 0.6}};
  EXPECT_THROW(TopologicalMarkov(bad_side, dervish_sensor_table()), UsageError);
  SensorTable bad_table = dervish_sensor_table();
  bad_table[0][0] = 1.5;
  EXPECT_THROW(TopologicalMarkov(dervish_map(), bad_table), UsageError);
  TopologicalMarkov m(dervish_map(), dervish_sensor_table());
  EXPECT_THROW(m.set_belief({1.0}), UsageError);
  EXPECT_THROW(m.set_belief({1.0, -0.1, 0, 0, 0, 0}), UsageError);
  EXPECT_THROW(m.action_update({{1.0}}), UsageError);
  EXPECT_THROW(m.index("5"), UsageError);
  TopologicalMarkov n(dervish_map(), dervish_sensor_table(), {.normalise = true});
  n.set_belief({0, 0, 0, 1.0, 0, 0});  // only at 3, where an open door on the right is impossible
  EXPECT_THROW(n.perception_update(kObservation), UsageError);
}

}  // namespace
}  // namespace locbench::baselines::global
