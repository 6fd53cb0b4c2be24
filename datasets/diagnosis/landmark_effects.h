#pragma once
// Simulated range-bearing landmark logs with hidden effects, for testing the diagnosis's landmark
// channel (algorithms/diagnosis/landmark_channel.h): a robot turns in place towards random
// waypoints and drives to them through a field of surveyed landmarks, with Vicon-like TRUEPOS
// (100 Hz, 1 mm / 1 mrad noise) and a camera at MRCLAM-like rates (an observation every
// U(0.2, 0.4) s of one landmark in view: range 0.5–6 m, bearing within ±0.5 rad). The map the log
// carries is the surveyed one; the effects change the camera or one landmark's true position.
// The truth of each effect is returned beside the log; the diagnosis never sees it.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "datasets/diagnosis/hidden_effects.h"

namespace locbench::sim {

struct LandmarkLogOptions {
  double duration = 600.0;                  // [s]
  int landmarks = 15;                       // placed uniformly in [−1, area + 1]²
  double area = 8.0;                        // waypoints in [0, area]² [m]
  double speed = 0.3;                       // [m/s]
  double turn_rate = 0.785;                 // turns in place [rad/s]
  double sigma_range = 0.03;                // camera range noise [m]
  double sigma_bearing = 0.01;              // camera bearing noise [rad]
  double min_range = 0.5, max_range = 6.0;  // [m]
  double field_of_view = 0.5;               // |bearing| ≤ this [rad]
  double truth_rate = 100.0;                // [Hz]
  double truth_noise_xy = 1e-3;             // [m]
  double truth_noise_theta = 1e-3;          // [rad]
  bool odometry = true;                     // log ODOM at 10 Hz (the truth's motion, 1% velocity noise)
};

// The landmark ids the generator can hide, with the unit of the magnitude.
std::vector<std::pair<std::string, std::string>> landmark_effect_ids();

// A log with ODOM (when options.odometry), TRUEPOS, landmark observations and the map.
// Throws UsageError for an unknown id or an invalid magnitude.
GeneratedLog generate_landmark_log(const std::vector<HiddenEffect>& effects, std::uint64_t seed,
                                   const LandmarkLogOptions& options = {});

// Adds a map and observations to a log that has TRUEPOS (e.g. generate_log's), the true pose read
// from that truth (interpolated). The effects' truth is added to g.truth.
void add_landmark_observations(GeneratedLog& g, const std::vector<HiddenEffect>& effects, std::uint64_t seed,
                               const LandmarkLogOptions& options = {});

}  // namespace locbench::sim
