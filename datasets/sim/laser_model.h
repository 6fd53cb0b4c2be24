#pragma once
// 2D laser scanner like the SICK LMS 200 (§5.4: 181 beams over −90°…90° at 1°, 5 Hz,
// σ = 5 mm), ray-cast against the world LineMap from the sensor's true pose (the robot's true
// pose composed with the mount). The sweep is instantaneous. Per beam, exclusively: with
// probability `dropout` → max_range; with probability `spurious` → uniform on [0, true range)
// (a short return from dust or a passer-by); otherwise
// scale · range + offset + N(0, σ²), clipped to [0, max_range]. No hit → max_range.
#include <vector>

#include "core/line_map.h"
#include "core/pose2.h"
#include "core/rng.h"
#include "core/scan.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

// A scan with what each beam really saw: the index of the world segment whose return it is, or
// kNoSegment for no return, a dropout or a spurious short return. The ground truth of the
// matcher experiments (point-assignment precision and recall).
struct LabelledScan {
  static constexpr int kNoSegment = -1;
  Scan scan;
  std::vector<int> segment;  // per beam
};

class LaserModel {
 public:
  LaserModel(const LaserConfig& c, const LineMap& world, Rng rng);
  // The model keeps a reference to `world`: a temporary map would dangle (every beam then misses).
  LaserModel(const LaserConfig& c, LineMap&& world, Rng rng) = delete;

  const std::vector<double>& bearings() const { return bearings_; }
  // Noise-free ranges from the robot at `robot` (max_range where nothing is hit).
  std::vector<double> true_ranges(const Pose2& robot) const;
  // A measured scan; sensor_pose = mount, timestamp as given.
  Scan measure(const Pose2& robot, double timestamp);
  // The same scan (same random draws) with the true segment of every beam.
  LabelledScan measure_labelled(const Pose2& robot, double timestamp);

 private:
  LaserConfig config_;
  const LineMap& world_;
  Rng rng_;
  std::vector<double> bearings_;
};

}  // namespace locbench::sim
