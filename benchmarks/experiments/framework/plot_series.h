#pragma once
// Chart series for reports (reports::Plot): trajectories and position error against distance
// travelled, built from trajectories the experiments already have.
#include <string>
#include <vector>

#include "core/trajectory.h"
#include "reports/report.h"

namespace locbench::experiments {

// The (x, y) path of a trajectory, thinned to at most `max_points` poses (first and last kept).
reports::PlotSeries trajectory_series(const std::string& name, const Trajectory& t,
                                      std::size_t max_points = 400);

// Distances 0, step, 2·step, … ≤ total [m].
std::vector<double> distance_grid(double total, double step);

// Position error of `estimate` against `truth` at the instants the truth has travelled each
// distance of `distances` (the first true pose at or past it); NaN where the truth never gets
// that far or the estimate does not cover the instant.
std::vector<double> error_at_distances(const Trajectory& truth, const Trajectory& estimate,
                                       const std::vector<double>& distances);

// Mean over runs at each grid point, over the runs with a finite value there; grid points no run
// reached are dropped. runs[k][i] is run k's value at distances[i].
reports::PlotSeries mean_over_runs(const std::string& name, const std::vector<double>& distances,
                                   const std::vector<std::vector<double>>& runs);

}  // namespace locbench::experiments
