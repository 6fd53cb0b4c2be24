// Experiment odometry/sim_corridor: dead-reckoning error on simulated corridor runs
// (Monte-Carlo). Two dead reckonings of the same ENCODER records:
// - odometry_nominal: with the nominal model the robot's software believes (what a robot does);
// - odometry_true_geometry: with the simulator's true wheel geometry, which leaves only the
//   random effects (quantization, floor noise, slip) — the gap between the two is the part of
//   the error that calibration can remove.
#include <fmt/format.h>

#include <array>
#include <cmath>

#include "core/checksum.h"
#include "core/dead_reckoning.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/trajectory_error.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/plot_series.h"
#include "experiment_framework/registry.h"
#include "pipelines/scenario_option.h"

namespace locbench::experiments::odometry_sim_corridor {

const ExperimentInfo kInfo{.name = "odometry/sim_corridor",
                           .description =
                               "Dead-reckoning error of simulated 10 m corridor runs (Trilobot-like, Monte-Carlo): "
                               "nominal model vs true geometry"};

struct RunErrors {
  double final_position = 0.0;  // [m]
  double final_heading = 0.0;   // [rad]
  double ape_rmse = 0.0;        // [m]
};

RunErrors errors_of(const Trajectory& truth, const Trajectory& estimate) {
  RunErrors e;
  const PoseErrors ape = absolute_pose_error(truth, estimate, Alignment::kNone);
  if (ape.translation.empty()) throw std::logic_error("no overlap between truth and odometry");
  e.final_position = ape.translation.back();
  e.final_heading = ape.rotation.back();
  e.ape_rmse = error_statistics(ape.translation).rmse;
  return e;
}

// Error against distance travelled is sampled every kDistanceStep metres of the true path.
constexpr double kDistanceStep = 0.25;  // [m]
const char* const kMethods[2] = {"odometry_nominal", "odometry_true_geometry"};

struct Options {
  int runs = 20;
  sim::Scenario scenario = sim::preset("corridor");
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.coded("scenario", o.scenario, scenario_json, scenario_option, "the simulated corridor run (datasets/sim)");
}

struct CorridorSetup {
  sim::Scenario scenario;
  nlohmann::json configuration;
};

// One Monte-Carlo run: per method final position/heading error, APE RMSE, error at each
// kDistanceStep of travel; run 0 also carries the trajectories for the report's chart.
struct CorridorRecord {
  std::array<double, 2> final_position{};
  std::array<double, 2> final_heading{};
  std::array<double, 2> ape_rmse{};
  std::array<std::vector<double>, 2> error_at_distance;
  std::size_t records = 0;
  double duration = 0.0;
  nlohmann::json trajectories;  // run 0 only: [PlotSeries as JSON]
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CorridorRecord, final_position, final_heading, ape_rmse, error_at_distance, records,
                                   duration, trajectories)

nlohmann::json series_json(const reports::PlotSeries& s) { return {{"name", s.name}, {"x", s.x}, {"y", s.y}}; }
reports::PlotSeries series_from(const nlohmann::json& j) {
  return {j.at("name").get<std::string>(), j.at("x").get<std::vector<double>>(), j.at("y").get<std::vector<double>>()};
}

class OdometrySimCorridor final : public MonteCarloExperiment<Options, CorridorSetup> {
 public:
  CorridorSetup setup(const Options& o, const McPlan& plan) const override { return {o.scenario, recorded(o, plan)}; }

  nlohmann::json run_task(const CorridorSetup& s, const McPlan& plan, int k) const override {
    const sim::SimulationResult sim = sim::simulate(s.scenario, plan.run_seed(k));
    const auto nominal = sim.log.nominal_model();
    if (!nominal) throw std::logic_error("simulated log lacks the nominal model PARAMs");
    const Trajectory truth = sim::true_trajectory(sim);
    // The robot knows its start pose; dead reckoning starts at the first ENCODER sample.
    const auto start = truth.pose_at(sim.log.encoders.front().t);
    if (!start) throw std::logic_error("first encoder sample outside the true trajectory");
    const Trajectory models[2] = {dead_reckon_encoders(sim.log.encoders, *nominal, *start),
                                  dead_reckon_encoders(sim.log.encoders, sim.robot.actual_model(), *start)};
    CorridorRecord r;
    const std::vector<double> grid = distance_grid(truth.path_length(), kDistanceStep);
    for (int m = 0; m < 2; ++m) {
      const RunErrors e = errors_of(truth, models[m]);
      r.final_position[m] = e.final_position;
      r.final_heading[m] = e.final_heading;
      r.ape_rmse[m] = e.ape_rmse;
      r.error_at_distance[m] = error_at_distances(truth, models[m], grid);
    }
    r.records = sim.log.record_count();
    r.duration = sim.duration;
    if (k == 0) {
      r.trajectories = {series_json(trajectory_series("truth", truth)),
                        series_json(trajectory_series(kMethods[0], models[0])),
                        series_json(trajectory_series(kMethods[1], models[1]))};
    }
    return r;
  }

  reports::ExperimentResults summarise(const CorridorSetup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.configuration);
    std::vector<double> pos[2], head[2], ape[2];
    std::vector<std::vector<std::vector<double>>> at_distance(2);  // [method][run][distance]
    CorridorRecord r;
    for (std::size_t k = 0; k < records.size(); ++k) {
      out.seeds.push_back(plan.run_seed(static_cast<int>(k)));
      r = records[k].get<CorridorRecord>();
      for (int m = 0; m < 2; ++m) {
        pos[m].push_back(r.final_position[m]);
        head[m].push_back(r.final_heading[m]);
        ape[m].push_back(r.ape_rmse[m]);
        at_distance[m].push_back(r.error_at_distance[m]);
      }
    }
    // Records and duration of the last run (all runs of the scenario are alike).
    out.datasets.push_back({"sim/" + s.scenario.name, "simulated", text_checksum(out.configuration["scenario"].dump()),
                            r.records, r.duration});
    const std::string dataset = "sim_" + s.scenario.name;
    for (int m = 0; m < 2; ++m) {
      out.results.push_back(
          reports::make_metric(kMethods[m], dataset, "final_position_error", "m", "monte_carlo_runs", pos[m]));
      out.results.push_back(
          reports::make_metric(kMethods[m], dataset, "final_heading_error", "rad", "monte_carlo_runs", head[m]));
      out.results.push_back(reports::make_metric(kMethods[m], dataset, "ape_rmse", "m", "monte_carlo_runs", ape[m]));
    }
    std::vector<reports::PlotSeries> paths;
    for (const auto& j : records.front().get<CorridorRecord>().trajectories) paths.push_back(series_from(j));
    out.plots.push_back(run_zero_trajectories("truth and dead reckoning", plan.run_seed(0), std::move(paths)));
    out.plots.push_back(mean_error_vs_distance({kMethods[0], kMethods[1]}, at_distance, kDistanceStep));
    return out;
  }
};

const Registration<OdometrySimCorridor> odometry_sim_corridor_registration(kInfo);

}  // namespace locbench::experiments::odometry_sim_corridor
