#pragma once
// A small log the tests write themselves, in the Freiburg form (CARMEN ODOM + FLASER and a
// .relations file): a robot drives an arc through a 7 m × 5 m room with a pillar, 181-beam scans
// (σ = 5 mm, seeded) every 0.5 s, odometry that over-reads distance by 3% and turns 1.5° too
// much per step. The relations are the true relative motions between consecutive scans.
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "core/line_map.h"
#include "core/log.h"
#include "core/pose2.h"
#include "core/scan.h"
#include "core/units.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/relations_writer.h"

namespace locbench::testing {

struct SmallRealLog {
  std::filesystem::path log, relations;
  std::size_t relation_count = 0;
};

inline LineMap small_room() {
  LineMap m;
  m.name = "small_room";
  const double r[][4] = {{0, 0, 7, 0},         {7, 0, 7, 5},         {7, 5, 0, 5},         {0, 5, 0, 0},
                         {3.0, 2.0, 3.6, 2.0}, {3.6, 2.0, 3.6, 2.6}, {3.6, 2.6, 3.0, 2.6}, {3.0, 2.6, 3.0, 2.0}};
  for (const auto& s : r) m.segments.push_back({{s[0], s[1]}, {s[2], s[3]}});
  return m;
}

inline Scan small_room_scan(const LineMap& room, const Pose2& pose, double t, std::mt19937_64& rng) {
  Scan s;
  s.timestamp = t;
  s.max_range = 81.9;
  s.bearings = even_bearings(181, -0.5 * kPi, 0.5 * kPi);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (double b : s.bearings) {
    const auto hit = room.ray_cast(pose.translation(), pose.theta + b, 80.0);
    s.ranges.push_back(hit ? hit->range + noise(rng) : 81.9);
  }
  return s;
}

// Writes <dir>/small.clf and <dir>/small.relations.
inline SmallRealLog write_small_real_log(const std::filesystem::path& dir, int scans = 24, unsigned seed = 7) {
  const LineMap room = small_room();
  std::mt19937_64 rng(seed);
  Log log;
  log.name = "small";
  Pose2 truth(1.0, 1.0, deg(10.0)), odom = truth;
  for (int k = 0; k < scans; ++k) {
    const double t = 100.0 + 0.5 * k;
    if (k > 0) {
      const Pose2 step(0.12, 0.0, deg(4.0));  // true motion per 0.5 s
      truth = truth * step;
      odom = odom * Pose2(1.03 * step.x, 0.0, step.theta + deg(1.5));
      log.relations.push_back({t - 0.5, t, step});
    }
    log.odometry.push_back({t, odom, 0.24, deg(8.0)});
    LaserReading r;
    r.scan = small_room_scan(room, truth, t, rng);
    log.laser.push_back(r);
  }
  SmallRealLog out;
  out.log = dir / "small.clf";
  out.relations = dir / "small.relations";
  out.relation_count = log.relations.size();
  locbench::io::write_carmen_log(log, out.log);
  locbench::io::write_relations(log.relations, out.relations);
  return out;
}

}  // namespace locbench::testing
