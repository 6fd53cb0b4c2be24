#pragma once
// Helpers shared by the simulator tests.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/diff_drive_odometry.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"

namespace locbench::sim::testing {

// The ideal robot with all noise off, driving `distance` straight from the origin.
inline Scenario quiet_straight(double distance) {
  Scenario s = preset("ideal");
  s.motion.kind = MotionKind::kStraight;
  s.motion.distance = distance;
  return s;
}

// Dead-reckons the log's ENCODER records with its nominal model (eq. 1.1–1.3), from `start`.
inline std::vector<Pose2> dead_reckon(const Log& log, const Pose2& start) {
  const NominalModel m = *log.nominal_model();
  std::vector<Pose2> out;
  Pose2 p = start;
  for (std::size_t i = 0; i < log.encoders.size(); ++i) {
    if (i > 0) {
      const auto& a = log.encoders[i - 1];
      const auto& b = log.encoders[i];
      p = odometry_step(p, displacement_from_ticks(m, b.left - a.left, b.right - a.right), m.wheelbase);
    }
    out.push_back(p);
  }
  return out;
}

// Per-sample differences of a cumulative WheelSample field.
template <typename F>
std::vector<double> increments(const std::vector<WheelSample>& w, F field) {
  std::vector<double> d;
  for (std::size_t i = 1; i < w.size(); ++i) {
    d.push_back(static_cast<double>(field(w[i])) - static_cast<double>(field(w[i - 1])));
  }
  return d;
}

}  // namespace locbench::sim::testing
