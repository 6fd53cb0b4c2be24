#pragma once
// Shared by the chapter-4 experiments: run the four compass-aided odometry filters on one
// simulated run and measure them against the simulator's truth.
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "algorithms/core/trajectory.h"
#include "datasets/sim/simulation_result.h"

namespace locbench::experiments {

inline constexpr int kNoiseFilters = 4;
// Result-name spellings, in the order of FilterRun::final_position_error.
inline const std::array<std::string, kNoiseFilters> kNoiseFilterNames = {
    "fixed_q_ekf", "adaptive_model_ekf", "sage_husa_aekf", "vb_akf"};

struct FilterRun {
  std::array<double, kNoiseFilters> final_position_error{};  // [m]
  std::array<double, kNoiseFilters> final_heading_error{};   // [rad]
  std::array<std::vector<double>, kNoiseFilters> nees;       // per step, pose NEES (3 dof)
  std::array<std::vector<double>, kNoiseFilters> nis;        // per compass update (1 dof)
  // For charts: each filter's estimate at every step, the truth, and dead reckoning with the
  // nominal model from the same start.
  std::array<Trajectory, kNoiseFilters> estimates;
  Trajectory truth;
  Trajectory odometry;
};

// Every filter's options as JSON, {"fixed_q_ekf": {…}, "adaptive_model_ekf": {…},
// "sage_husa_aekf": {…}, "vb_akf": {…}}: the published settings of §4.5 in SI, with diag P(0)
// set to `initial_covariance` [m², m², rad²] (the thesis uses 0).
nlohmann::json default_filter_options(const Eigen::Vector3d& initial_covariance);

// Runs the four filters with `filter_options` (as above; strict: unknown keys are a UsageError).
FilterRun run_noise_filters(const sim::SimulationResult& result,
                            const nlohmann::json& filter_options);

}  // namespace locbench::experiments
