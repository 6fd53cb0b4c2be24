// Google Benchmark kernels of global localization (baselines/global): cost against grid
// resolution and particle count, and the four localizers over one simulated log.
//   BM_GridMarkovUpdate/cell_mm/angle_ddeg  one action update (0.2 m forward, 2° turn) and one
//       perception update (20 beams) of grid Markov over the 8 m room at cell_mm × cell_mm ×
//       angle_ddeg/10 degrees: 300 mm × 10°, 200 mm × 5° (the experiments' default), 150 mm × 2°,
//       and the slides' 150 mm × 1° (54 × 54 × 360 = 1 049 760 cells).
//   BM_MclUpdate/particles  one MCL update (motion sampling, likelihood field, low-variance
//       resampling) at a fixed particle count (KLD off): 100 … 10 000.
//   BM_Replay/method        a whole 60 s room_laser log (299 scans) through mcl, grid_markov,
//       ekf_eap, kalman_line_features (global methods from an unknown start, trackers from the
//       truth); `per_scan_us` is the mean time per scan.
// Counters: `cells` / `particles`, `memory_bytes` (belief or particles + likelihood field).
// Compare ratios within one run only (the machine is shared).
#include <benchmark/benchmark.h>

#include <memory>

#include "baselines/global/grid_markov.h"
#include "baselines/global/monte_carlo_localization.h"
#include "core/units.h"
#include "datasets/sim/laser_model.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/simulator.h"
#include "datasets/sim/worlds.h"
#include "pipelines/global_harness.h"

namespace locbench::speed {
namespace {

const Pose2 kTruth(2.0, 1.0, deg(46.0));

const Scan& room_scan() {
  static const Scan s = [] {
    sim::LaserConfig c;
    c.timing.enabled = true;
    c.noise = mm(5.0);
    static const LineMap world = sim::room_world();  // the model keeps a reference to it
    sim::LaserModel laser(c, world, Rng(7));
    return laser.measure(kTruth, 0.0);
  }();
  return s;
}

void BM_GridMarkovUpdate(benchmark::State& state) {
  baselines::global::GridMarkovOptions o;
  o.cell_size = static_cast<double>(state.range(0)) / 1000.0;
  o.angular_cell = deg(static_cast<double>(state.range(1)) / 10.0);
  baselines::global::GridMarkov g(sim::room_world(), o);
  const Scan& scan = room_scan();
  for (auto _ : state) {
    g.action_update({deg(1.0), 0.2, deg(1.0)});
    g.perception_update(scan);
    benchmark::DoNotOptimize(g.belief().data());
  }
  state.counters["cells"] = static_cast<double>(g.cell_count());
  state.counters["memory_bytes"] = static_cast<double>(g.memory_bytes());
}
BENCHMARK(BM_GridMarkovUpdate)
    ->Args({300, 100})
    ->Args({200, 50})
    ->Args({150, 20})
    ->Args({150, 10})
    ->Unit(benchmark::kMillisecond);

void BM_MclUpdate(benchmark::State& state) {
  baselines::global::MclOptions o;
  o.kld = false;
  o.initial_particles = o.max_particles = static_cast<int>(state.range(0));
  o.min_particles = std::min(o.min_particles, o.max_particles);
  o.update_min_distance = 0.0;
  o.update_min_angle = 0.0;
  baselines::global::MonteCarloLocalization mcl(sim::room_world(), o, 3);
  const Scan& scan = room_scan();
  Pose2 odo;
  for (auto _ : state) {
    odo = odo * Pose2(0.1, 0.0, deg(1.0));
    mcl.update(odo, scan);
    benchmark::DoNotOptimize(mcl.estimate());
  }
  state.counters["particles"] = static_cast<double>(mcl.particle_count());
  state.counters["memory_bytes"] = static_cast<double>(mcl.memory_bytes());
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_MclUpdate)->RangeMultiplier(10)->Range(100, 10000)->Complexity()->Unit(benchmark::kMicrosecond);

const sim::SimulationResult& replay_log() {
  static const sim::SimulationResult r = sim::simulate(sim::preset("room_laser"), 3);
  return r;
}

void BM_Replay(benchmark::State& state) {
  const std::string method = experiments::global::method_names()[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(method);
  const auto& r = replay_log();
  const auto steps = experiments::global::scan_steps(r.log);
  const LineMap room = sim::room_world();
  const auto options = experiments::global::default_method_options();
  std::size_t memory = 0;
  for (auto _ : state) {
    auto loc = experiments::global::make_localizer(method, room, options, steps.front().reference, 5);
    for (const auto& s : steps) loc->step(s);
    memory = loc->memory_bytes();
    benchmark::DoNotOptimize(loc->pose());
  }
  state.counters["scans"] = static_cast<double>(steps.size());
  state.counters["per_scan_us"] =
      benchmark::Counter(static_cast<double>(steps.size()) * 1e-6,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["memory_bytes"] = static_cast<double>(memory);
}
BENCHMARK(BM_Replay)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace locbench::speed
