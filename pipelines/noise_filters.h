#pragma once
// Shared by the chapter-4 experiments: run the four compass-aided odometry filters on one
// simulated run and measure them against the simulator's truth.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/trajectory.h"
#include "core/units.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario.h"
#include "datasets/sim/simulation_result.h"
#include "experiment_framework/experiment_options.h"
#include "pipelines/scenario_option.h"
#include "reports/report.h"

namespace locbench::experiments {

inline constexpr int kNoiseFilters = 4;
// Result-name spellings, in the order of FilterRun::final_position_error.
inline const std::array<std::string, kNoiseFilters> kNoiseFilterNames = {"fixed_q_ekf", "adaptive_model_ekf",
                                                                         "sage_husa_aekf", "vb_akf"};

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
FilterRun run_noise_filters(const sim::SimulationResult& result, const nlohmann::json& filter_options);

// P(0) = diag(1 mm², 1 mm², 0.3°²): the thesis starts from P(0) = 0, which makes the NEES of
// the first samples undefined; the effect on the final error is below a millimetre.
inline const Eigen::Vector3d kFilterInitialCovariance{1e-6, 1e-6, deg(0.3) * deg(0.3)};

// The four filters' samples over Monte-Carlo runs.
struct FilterSamples {
  std::vector<double> final_error[kNoiseFilters];
  std::vector<double> heading_error[kNoiseFilters];
  std::vector<std::vector<double>> nees[kNoiseFilters];
  std::vector<std::vector<double>> nis[kNoiseFilters];
};

// One Monte-Carlo run of the four filters, as a task record (see monte_carlo.h).
struct FilterRecord {
  std::array<double, kNoiseFilters> final_error{};
  std::array<double, kNoiseFilters> heading_error{};
  std::array<std::vector<double>, kNoiseFilters> nees;
  std::array<std::vector<double>, kNoiseFilters> nis;
  std::size_t records = 0;
  double duration = 0.0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FilterRecord, final_error, heading_error, nees, nis, records, duration)

FilterRecord record_of(const FilterRun& r, const sim::SimulationResult& sim);
void collect(const FilterRecord& r, FilterSamples& s);

// Truncates series to a common length so they can be averaged per step.
std::vector<std::vector<double>> common_length(std::vector<std::vector<double>> v);

// Per filter: final position and heading error, time-averaged NEES and NIS, and a note on
// their χ² bands.
void add_filter_results(reports::ExperimentResults& out, const std::string& dataset, const FilterSamples& s);

// The options the filter experiments share: simulated corridor runs filtered by the four
// filters (noise/tables_4_1_4_2, noise/encoder_resolution_sweep).
struct CorridorFilterOptions {
  int runs = 10;
  sim::Scenario scenario = sim::preset("corridor");
  nlohmann::json filters = default_filter_options(kFilterInitialCovariance);  // run_noise_filters
};
template <class V>
void visit_corridor_filter_fields(V& v, CorridorFilterOptions& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.coded("scenario", o.scenario, scenario_json, scenario_option, "the simulated corridor run (datasets/sim)");
  v.field("filters", o.filters, "", Range{}, "each filter's options (run_noise_filters)");
}

}  // namespace locbench::experiments
