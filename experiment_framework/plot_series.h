#pragma once
// Chart series for reports (reports::Plot): trajectories and position error against distance
// travelled, built from trajectories the experiments already have.
#include <cstdint>
#include <string>
#include <vector>

#include "core/trajectory.h"
#include "reports/report.h"

namespace locbench::experiments {

// The (x, y) path of a trajectory, thinned to at most `max_points` poses (first and last kept).
reports::PlotSeries trajectory_series(const std::string& name, const Trajectory& t, std::size_t max_points = 400);

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

// A "trajectory" plot of Monte-Carlo run 0 (seed `seed`): one path per series, titled
// "Trajectories of run 0: <what>".
reports::Plot run_zero_trajectories(const std::string& what, std::uint64_t seed,
                                    std::vector<reports::PlotSeries> paths);

// The "error_vs_distance" plot: per method, the mean over runs of its position error every `step`
// metres of the true path. errors[m][k] is method m's error_at_distances of run k.
reports::Plot mean_error_vs_distance(const std::vector<std::string>& methods,
                                     const std::vector<std::vector<std::vector<double>>>& errors, double step);

}  // namespace locbench::experiments

namespace locbench::experiments {

// A sample thinned for a "cdf" plot: its `n` evenly spaced order statistics (all of it when it
// has at most n finite values), so the drawn CDF matches the full sample's to 1/n.
reports::PlotSeries cdf_samples(const std::string& name, std::vector<double> values, std::size_t n = 200);

// A "cdf" plot of error samples (one series per method, e.g. from cdf_samples): the error
// distribution of each method, as evo shows APE/RPE.
reports::Plot error_cdf_plot(std::string name, std::string title, std::string x_label, std::string x_unit,
                             std::vector<reports::PlotSeries> samples, std::string note);

// A log's relative-pose error CDFs, one series per method: "<dataset>_rpe_translation_cdf" (mm)
// and "<dataset>_rpe_rotation_cdf" (deg), titled "<dataset>: <what> translation/rotation error".
// translation_m[k] and rotation_rad[k] are method k's errors per relation (SI).
std::vector<reports::Plot> relative_pose_error_cdfs(const std::string& dataset, const std::string& what,
                                                    const std::vector<std::string>& methods,
                                                    const std::vector<std::vector<double>>& translation_m,
                                                    const std::vector<std::vector<double>>& rotation_rad,
                                                    const std::string& note);

// Binned means of y against x: the finite pairs sorted by x, cut into `bins` bins of equal count;
// per bin the mean x and mean y (a bin needs at least 3 pairs).
reports::PlotSeries binned_means(const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
                                 std::size_t bins = 12);

}  // namespace locbench::experiments
