#pragma once
// Test helper: a simulated log as (odometry pose, scan, true pose) per scan, and two logs
// spliced into one kidnapping (the odometry continues smoothly while the robot is carried to
// the second log's start).
#include <vector>

#include "core/units.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"

namespace locbench::baselines::global::test {

struct Step {
  double t = 0.0;
  Pose2 odometry;
  Scan scan;
  Pose2 truth;
};

inline std::vector<Step> steps_of(const sim::SimulationResult& r) {
  std::vector<Step> out;
  for (const LaserReading& l : r.log.laser) {
    const auto odo = locbench::io::interpolate_odometry(r.log, l.scan.timestamp);
    const auto truth = locbench::io::interpolate_truth(r.log, l.scan.timestamp);
    if (odo && truth) out.push_back({l.scan.timestamp, *odo, l.scan, *truth});
  }
  return out;
}

// The room_laser preset (8 m room, ~65 s) from its own start, seeded.
inline std::vector<Step> room_run(std::uint64_t seed) {
  return steps_of(sim::simulate(sim::preset("room_laser"), seed));
}

// A second drive in the room from the opposite corner.
inline std::vector<Step> room_run_b(std::uint64_t seed) {
  sim::Scenario s = sim::preset("room_laser");
  s.start = Pose2(6.5, 6.5, deg(-90.0));
  s.motion.waypoints = {{6.5, 3.0}, {2.5, 3.0}, {2.5, 1.5}};
  return steps_of(sim::simulate(s, seed));
}

// `b` after `a`, b's odometry re-expressed to continue from a's last odometry pose.
inline std::vector<Step> kidnapped(std::vector<Step> a, const std::vector<Step>& b) {
  const Pose2 end = a.back().odometry;
  const Pose2 b0 = b.front().odometry;
  const double t0 = a.back().t + 0.2 - b.front().t;
  for (Step s : b) {
    s.odometry = end * between(b0, s.odometry);
    s.t += t0;
    s.scan.timestamp += t0;
    a.push_back(s);
  }
  return a;
}

inline double position_error(const Pose2& a, const Pose2& b) { return translation_distance(a, b); }

}  // namespace locbench::baselines::global::test
