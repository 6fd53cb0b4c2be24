// Worlds: the thesis's 8 m room (14 segments), the corridor, JSON world files.
#include "datasets/sim/worlds.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "core/errors.h"
#include "datasets/sim/presets.h"
#include "tests/test_data.h"

namespace locbench::sim {
namespace {

TEST(RoomWorld, HasExactly14Segments) {
  const LineMap room = room_world();
  EXPECT_EQ(room.segments.size(), 14u);
  EXPECT_EQ(room.name, "room");
  for (const auto& s : room.segments) {
    for (const auto& p : {s.p1, s.p2}) {
      EXPECT_GE(p.x(), 0.0);
      EXPECT_LE(p.x(), 8.0);
      EXPECT_GE(p.y(), 0.0);
      EXPECT_LE(p.y(), 8.0);
    }
  }
}

TEST(RoomWorld, ObstaclesHaveTheThesisSizes) {
  std::multiset<std::pair<double, double>> sizes;
  for (const auto& r : room_obstacles()) {
    const Eigen::Vector2d d = r.max - r.min;
    sizes.insert({std::max(d.x(), d.y()), std::min(d.x(), d.y())});
  }
  EXPECT_EQ(sizes, (std::multiset<std::pair<double, double>>{{2, 1}, {2, 1}, {2, 2}}));
}

TEST(RoomWorld, ThesisStartPoseIsFreeAndSeesSeveralSegments) {
  const Eigen::Vector2d start(2.0, 1.0);
  const LineMap room = room_world();
  for (const auto& r : room_obstacles()) EXPECT_FALSE(r.contains(start));
  for (const auto& s : room.segments) EXPECT_GE(distance_to_segment(s, start), 1.0);
  // The LMS 200's 181 beams from (2.0, 1.0, 46°) hit 9 distinct segments, including
  // non-parallel ones in every direction.
  std::set<std::size_t> seen;
  for (int i = 0; i <= 180; ++i) {
    const auto hit = room.ray_cast(start, deg(46.0) + deg(i - 90.0), 8.0);
    ASSERT_TRUE(hit.has_value()) << i;  // every beam returns within 8 m
    seen.insert(hit->segment);
  }
  EXPECT_EQ(seen, (std::set<std::size_t>{0, 1, 2, 3, 4, 7, 10, 11, 12}));
}

TEST(RoomWorld, RoomLaserWaypointsAreInFreeSpace) {
  for (const auto& w : preset("room_laser").motion.waypoints) {
    for (const auto& r : room_obstacles()) EXPECT_FALSE(r.contains(w));
    for (const auto& s : room_world().segments) EXPECT_GE(distance_to_segment(s, w), 0.9);
  }
}

TEST(CorridorWorld, IsClosedAndHasTheConfiguredWidthAndLength) {
  const LineMap c = corridor_world(12.0, 1.8);
  ASSERT_EQ(c.segments.size(), 4u);
  const auto up = c.ray_cast({3.0, 0.0}, kPi / 2, 10.0);
  const auto down = c.ray_cast({3.0, 0.0}, -kPi / 2, 10.0);
  const auto ahead = c.ray_cast({3.0, 0.0}, 0.0, 20.0);
  ASSERT_TRUE(up && down && ahead);
  EXPECT_DOUBLE_EQ(up->range + down->range, 1.8);
  EXPECT_DOUBLE_EQ(ahead->range, 9.0);
}

TEST(WorldJson, ReadsNameAndSegmentsInMetres) {
  const LineMap m = world_from_json(
      nlohmann::json::parse(R"({"name": "lab", "segments": [[0, 0, 4, 0], [4, 0, 4, 3.5]]})"), "lab.json");
  EXPECT_EQ(m.name, "lab");
  ASSERT_EQ(m.segments.size(), 2u);
  EXPECT_EQ(m.segments[1].p2, Eigen::Vector2d(4.0, 3.5));
}

TEST(WorldJson, BadFilesAreInputErrorsNamingTheFileAndTheProblem) {
  locbench::testing::ScratchDir dir;
  const auto write = [&](const char* name, const char* text) {
    std::ofstream(dir.file(name)) << text;
    return dir.file(name);
  };
  const std::vector<std::pair<std::filesystem::path, std::string>> cases = {
      {write("syntax.json", "{\"segments\": [[0,0,1,1],}"), "invalid JSON"},
      {write("no_segments.json", "{\"name\": \"x\"}"), "segments: missing"},
      {write("short.json", "{\"segments\": [[0,0,1]]}"), "segments[0]"},
      {write("text.json", "{\"segments\": [[0,0,1,\"a\"]]}"), "segments[0][3]"},
      {write("zero.json", "{\"segments\": [[1,1,1,1]]}"), "zero-length"},
      {write("extra.json", "{\"segments\": [], \"scale\": 2}"), "scale: unknown key (expected one of: "},
      {dir.file("absent.json"), "cannot open"},
  };
  for (const auto& [path, fragment] : cases) {
    try {
      load_world(path);
      ADD_FAILURE() << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path.string());
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

TEST(BuildWorld, MakesTheWorldAScenarioNames) {
  WorldConfig w;
  EXPECT_TRUE(build_world(w).segments.empty());
  w.kind = WorldKind::kRoom;
  EXPECT_EQ(build_world(w).segments.size(), 14u);
  w.kind = WorldKind::kCorridor;
  w.corridor_length = 20.0;
  EXPECT_EQ(build_world(w).segments[0].p2.x(), 20.0);
  w.kind = WorldKind::kInline;
  w.segments = {{0, 0, 1, 0}};
  EXPECT_EQ(build_world(w).segments.size(), 1u);
}

TEST(RandomRoom, IsDeterministicClosedAndHasFourSegmentsPerBox) {
  Rng a(7), b(7);
  const LineMap r1 = random_room(a), r2 = random_room(b);
  ASSERT_EQ(r1.segments.size(), r2.segments.size());
  EXPECT_EQ(r1.segments.size() % 4, 0u);
  EXPECT_GE(r1.segments.size(), 8u);  // walls + at least one box in a ≥ 6 m room
  for (std::size_t i = 0; i < r1.segments.size(); ++i) {
    EXPECT_EQ(r1.segments[i].p1, r2.segments[i].p1);
    EXPECT_GT(r1.segments[i].length(), 0.4);
  }
}

TEST(RandomRoom, FreeSpaceExcludesBoxesWallsAndTheOutside) {
  const LineMap room = room_world();
  EXPECT_TRUE(in_free_space(room, {2.0, 1.0}, 0.3));   // the thesis pose
  EXPECT_TRUE(in_free_space(room, {2.0, 5.0}, 0.3));   // left of box B: ray crosses B twice
  EXPECT_FALSE(in_free_space(room, {5.0, 5.0}, 0.3));  // inside B
  EXPECT_FALSE(in_free_space(room, {6.0, 0.5}, 0.1));  // inside A (against the bottom wall)
  EXPECT_FALSE(in_free_space(room, {0.5, 6.0}, 0.1));  // inside C (against the left wall)
  EXPECT_FALSE(in_free_space(room, {9.0, 1.0}, 0.1));  // outside the room
  EXPECT_FALSE(in_free_space(room, {2.0, 0.2}, 0.3));  // too close to the bottom wall
}

TEST(TiledRooms, RepeatTheRoomAndKeepTheFirstRoomsView) {
  const LineMap m = tiled_rooms(100);
  EXPECT_EQ(m.segments.size(), 1400u);
  const LineMap room = room_world();
  const Eigen::Vector2d o(2.0, 1.0);
  for (double a = 0.0; a < 6.28; a += 0.1) {
    const auto h1 = room.ray_cast(o, a, 8.0);
    const auto h2 = m.ray_cast(o, a, 8.0);
    ASSERT_EQ(h1.has_value(), h2.has_value());
    if (h1) {
      EXPECT_NEAR(h1->range, h2->range, 1e-12);
    }
  }
  EXPECT_THROW(tiled_rooms(0), UsageError);
}

}  // namespace
}  // namespace locbench::sim
