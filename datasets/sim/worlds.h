#pragma once
// Worlds the simulated laser sees, as LineMaps in metres.
//
// The thesis's room (§5.4): 8 m × 8 m, origin at the lower-left corner, obstacles 2 × 1 m,
// 2 × 2 m and 2 × 1 m, 14 segments in all; its figure is lost, so the placement is ours:
// the two 2 × 1 m blocks stand against walls (3 exposed sides each; the wall behind stays one
// segment) and the 2 × 2 m block stands free (4 sides): 4 + 3 + 3 + 4 = 14.
//   block A 2 × 1 m against the bottom wall: x ∈ [5, 7], y ∈ [0, 1]
//   block B 2 × 2 m free-standing:           x ∈ [4, 6], y ∈ [4, 6]
//   block C 1 × 2 m against the left wall:   x ∈ [0, 1], y ∈ [5, 7]
// From the thesis's pose (2.0, 1.0, 46°) the LMS 200's half-plane sees 9 of them, in all four
// directions (walls, both faces of B and of C, the left face of A).
#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/line_map.h"
#include "core/rng.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

struct Rect {
  Eigen::Vector2d min;
  Eigen::Vector2d max;
  bool contains(const Eigen::Vector2d& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
};

inline constexpr double kRoomSize = 8.0;  // [m]
// The three obstacles of the room, in the order A, B, C above.
std::vector<Rect> room_obstacles();
// The 14-segment room ("room").
LineMap room_world();
// A random rectangular room for the matcher experiments: width and height uniform in
// [min_size, max_size], origin at the lower-left corner, `boxes` free-standing axis-aligned
// boxes (sides uniform in [0.5, 2] m) that keep `clearance` from the walls and from each other
// (placement retried; fewer boxes when the room is full). 4 + 4·boxes segments. Deterministic
// for a given Rng state.
struct RandomRoomOptions {
  double min_size = 6.0;   // [m]
  double max_size = 12.0;  // [m]
  int boxes = 3;
  double clearance = 1.0;  // [m]
};
LineMap random_room(Rng& rng, const RandomRoomOptions& options = {});
// Free space of a room made by random_room or room_world: a point at least `margin` from every
// segment and outside every box (for drawing random robot poses).
bool in_free_space(const LineMap& room, const Eigen::Vector2d& p, double margin);
// `count` copies of the 14-segment room tiled in a square grid 10 m apart (room i at
// ((i mod k)·10, (i div k)·10), k = ⌈√count⌉): maps of 14·count segments in which the view from
// the first room is the same as in room_world() (for cost against map size).
LineMap tiled_rooms(int count);

// A closed corridor along +x: walls y = ±width/2 for x ∈ [0, length] and end walls at x = 0 and
// x = length ("corridor").
LineMap corridor_world(double length, double width = 1.8);
// {"name": ..., "segments": [[x1, y1, x2, y2], ...]} in metres; throws InputError naming
// `source` on a malformed document, an unknown key or a zero-length segment.
LineMap world_from_json(const nlohmann::json& j, const std::string& source);
LineMap load_world(const std::filesystem::path& path);
// The world a scenario names.
LineMap build_world(const WorldConfig& w);

}  // namespace locbench::sim
