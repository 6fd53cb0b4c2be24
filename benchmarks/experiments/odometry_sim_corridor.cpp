// Experiment odometry/sim_corridor: dead-reckoning error on simulated corridor runs
// (Monte-Carlo). Two dead reckonings of the same ENCODER records:
// - odometry_nominal: with the nominal model the robot's software believes (what a robot does);
// - odometry_true_geometry: with the simulator's true wheel geometry, which leaves only the
//   random effects (quantization, floor noise, slip) — the gap between the two is the part of
//   the error that calibration can remove.
#include <cmath>

#include "algorithms/core/dead_reckoning.h"
#include "algorithms/core/errors.h"
#include "algorithms/core/rng.h"
#include "algorithms/core/trajectory_error.h"
#include "benchmarks/experiments/experiment.h"
#include "benchmarks/experiments/experiments_list.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "reports/checksum.h"

namespace locbench::experiments {
namespace {

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

class OdometrySimCorridor final : public Experiment {
 public:
  std::string name() const override { return "odometry/sim_corridor"; }
  std::string description() const override {
    return "Dead-reckoning error of simulated 10 m corridor runs (Trilobot-like, Monte-Carlo): "
           "nominal model vs true geometry";
  }
  nlohmann::json default_config() const override {
    return {{"runs", 20}, {"scenario", sim::to_json(sim::preset("corridor"))}};
  }

  reports::ExperimentResults run(const nlohmann::json& config,
                                 const RunOptions& options) const override {
    reports::ExperimentResults out;
    out.experiment = name();
    out.description = description();
    const int runs = monte_carlo_runs(*this, config, options);
    const sim::Scenario scenario = sim::scenario_from_json(config.at("scenario"), "<configuration>");
    out.configuration = config;
    out.configuration["runs"] = runs;
    out.configuration["scenario"] = sim::to_json(scenario);

    std::vector<double> pos[2], head[2], ape[2];
    std::size_t records = 0;
    double duration = 0.0;
    for (int k = 0; k < runs; ++k) {
      options.report_progress(static_cast<double>(k) / runs);
      const std::uint64_t seed = Rng::derive_seed(options.seed, static_cast<std::uint64_t>(k));
      out.seeds.push_back(seed);
      const sim::SimulationResult sim = sim::simulate(scenario, seed);
      const auto nominal = sim.log.nominal_model();
      if (!nominal) throw std::logic_error("simulated log lacks the nominal model PARAMs");
      const Trajectory truth = sim::true_trajectory(sim);
      // The robot knows its start pose; dead reckoning starts at the first ENCODER sample.
      const auto start = truth.pose_at(sim.log.encoders.front().t);
      if (!start) throw std::logic_error("first encoder sample outside the true trajectory");
      const Trajectory models[2] = {
          dead_reckon_encoders(sim.log.encoders, *nominal, *start),
          dead_reckon_encoders(sim.log.encoders, sim.robot.actual_model(), *start)};
      for (int m = 0; m < 2; ++m) {
        const RunErrors e = errors_of(truth, models[m]);
        pos[m].push_back(e.final_position);
        head[m].push_back(e.final_heading);
        ape[m].push_back(e.ape_rmse);
      }
      records = sim.log.record_count();
      duration = sim.duration;
    }
    options.report_progress(1.0);
    out.datasets.push_back({"sim/" + scenario.name, "simulated",
                            reports::text_checksum(out.configuration["scenario"].dump()), records,
                            duration});
    const std::string dataset = "sim_" + scenario.name;
    const char* methods[2] = {"odometry_nominal", "odometry_true_geometry"};
    for (int m = 0; m < 2; ++m) {
      out.results.push_back(reports::make_metric(methods[m], dataset, "final_position_error", "m",
                                                 "monte_carlo_runs", pos[m]));
      out.results.push_back(reports::make_metric(methods[m], dataset, "final_heading_error",
                                                 "rad", "monte_carlo_runs", head[m]));
      out.results.push_back(reports::make_metric(methods[m], dataset, "ape_rmse", "m",
                                                 "monte_carlo_runs", ape[m]));
    }
    return out;
  }
};

}  // namespace

std::unique_ptr<Experiment> make_odometry_sim_corridor() {
  return std::make_unique<OdometrySimCorridor>();
}

}  // namespace locbench::experiments
