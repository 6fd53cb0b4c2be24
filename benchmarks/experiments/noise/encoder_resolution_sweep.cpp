// Experiment noise/encoder_resolution_sweep: the four compass-aided filters of Tables 4.1/4.2
// (harness/noise_filters.h) from Pioneer-like (0.0152 mm per tick) to Trilobot-like (12.64 mm
// per tick) encoders: final error and NEES consistency.
#include <fmt/format.h>

#include <vector>

#include "core/checksum.h"
#include "core/errors.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"
#include "pipelines/noise_filters.h"

namespace locbench::experiments::noise_encoder_resolution_sweep {

const ExperimentInfo kInfo{.name = "noise/encoder_resolution_sweep",
                           .description =
                               "The four compass-aided filters from Pioneer-like (0.0152 mm/tick) to Trilobot-like "
                               "(12.64 mm/tick) encoders: final error and NEES consistency"};

struct SweepSetup {
  std::vector<double> resolutions;       // [m per tick]
  std::vector<sim::Scenario> scenarios;  // one per resolution
  nlohmann::json filters;
  nlohmann::json configuration;
};

struct Options : CorridorFilterOptions {
  Options() { runs = 5; }
  std::vector<double> meters_per_tick = {0.0000152, 0.0001, 0.001, 0.005, 0.01264};
};
template <class V>
void visit_fields(V& v, Options& o) {
  visit_corridor_filter_fields(v, o);
  v.field("meters_per_tick", o.meters_per_tick, "m", positive(), "the encoder resolutions swept");
}

class EncoderResolutionSweep final : public MonteCarloExperiment<Options, SweepSetup> {
 public:
  SweepSetup setup(const Options& o, const McPlan& plan) const override {
    SweepSetup u;
    u.filters = o.filters;
    u.configuration = recorded(o, plan);
    for (double c : o.meters_per_tick) {
      sim::Scenario s = o.scenario;
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
    return record_of(run_noise_filters(r, u.filters), r);
  }

  reports::ExperimentResults summarise(const SweepSetup& u, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(u.configuration);
    for (std::size_t i = 0; i < u.scenarios.size(); ++i) {
      FilterSamples fs;
      for (int k = 0; k < plan.runs; ++k) {
        out.seeds.push_back(plan.run_seed(k));
        collect(records[i * static_cast<std::size_t>(plan.runs) + static_cast<std::size_t>(k)].get<FilterRecord>(), fs);
      }
      const std::string key = reports::key_part(fmt::format("sim_corridor_{:.4g}mm_per_tick", u.resolutions[i] * 1e3));
      out.datasets.push_back({key, "simulated", text_checksum(sim::to_json(u.scenarios[i]).dump()), 0, 0.0});
      add_filter_results(out, key, fs);
    }
    return out;
  }
};

const Registration<EncoderResolutionSweep> noise_encoder_resolution_sweep_registration(kInfo);

}  // namespace locbench::experiments::noise_encoder_resolution_sweep
