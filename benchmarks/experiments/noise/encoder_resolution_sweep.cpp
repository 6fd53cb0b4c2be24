// Experiment noise/encoder_resolution_sweep: the four compass-aided filters of Tables 4.1/4.2
// (harness/noise_filters.h) from Pioneer-like (0.0152 mm per tick) to Trilobot-like (12.64 mm
// per tick) encoders: final error and NEES consistency.
#include <fmt/format.h>

#include <vector>

#include "core/errors.h"
#include "benchmarks/experiments/framework/monte_carlo.h"
#include "benchmarks/experiments/framework/registry.h"
#include "benchmarks/experiments/harness/noise_filters.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "reports/checksum.h"

namespace locbench::experiments {
namespace {

struct SweepSetup {
  std::vector<double> resolutions;      // [m per tick]
  std::vector<sim::Scenario> scenarios;  // one per resolution
  nlohmann::json configuration;
};

class EncoderResolutionSweep final : public MonteCarloExperiment<SweepSetup> {
 public:
  std::string name() const override { return "noise/encoder_resolution_sweep"; }
  std::string description() const override {
    return "The four compass-aided filters from Pioneer-like (0.0152 mm/tick) to Trilobot-like "
           "(12.64 mm/tick) encoders: final error and NEES consistency";
  }
  nlohmann::json default_config() const override {
    return {{"runs", 5},
            {"scenario", sim::to_json(sim::preset("corridor"))},
            {"filters", default_filter_options(kFilterInitialCovariance)},
            {"meters_per_tick", {0.0000152, 0.0001, 0.001, 0.005, 0.01264}}};
  }
  SweepSetup setup(const nlohmann::json& config, const McPlan& plan) const override {
    SweepSetup u;
    const sim::Scenario base = corridor_from(config);
    u.configuration = config;
    u.configuration["runs"] = plan.runs;
    for (double c : config.at("meters_per_tick").get<std::vector<double>>()) {
      if (!(c > 0.0)) throw UsageError(name() + ": meters_per_tick must be > 0");
      sim::Scenario s = base;
      // Counts per wheel revolution giving c metres per tick on the nominal left wheel.
      s.robot.encoder.gear_ratio = 1.0;
      s.robot.encoder.counts_per_rev = kPi * s.robot.nominal.diameter_left / c;
      u.resolutions.push_back(c);
      u.scenarios.push_back(s);
    }
    return u;
  }

  // Task t is run t % runs at resolution t / runs (every resolution sees the same seeds).
  int tasks(const SweepSetup& u, const McPlan& plan) const override {
    return static_cast<int>(u.scenarios.size()) * plan.runs;
  }

  nlohmann::json run_task(const SweepSetup& u, const McPlan& plan, int task) const override {
    const sim::Scenario& s = u.scenarios[static_cast<std::size_t>(task / plan.runs)];
    const sim::SimulationResult r = sim::simulate(s, plan.run_seed(task % plan.runs));
    return record_of(run_noise_filters(r, u.configuration.at("filters")), r);
  }

  reports::ExperimentResults summarise(const SweepSetup& u, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(u.configuration);
    for (std::size_t i = 0; i < u.scenarios.size(); ++i) {
      FilterSamples fs;
      for (int k = 0; k < plan.runs; ++k) {
        out.seeds.push_back(plan.run_seed(k));
        collect(records[i * static_cast<std::size_t>(plan.runs) + static_cast<std::size_t>(k)]
                    .get<FilterRecord>(),
                fs);
      }
      const std::string key =
          reports::key_part(fmt::format("sim_corridor_{:.4g}mm_per_tick", u.resolutions[i] * 1e3));
      out.datasets.push_back({key, "simulated",
                              reports::text_checksum(sim::to_json(u.scenarios[i]).dump()), 0, 0.0});
      add_filter_results(out, key, fs);
    }
    return out;
  }
};

const Registration<EncoderResolutionSweep> noise_encoder_resolution_sweep_registration;

}  // namespace
}  // namespace locbench::experiments
