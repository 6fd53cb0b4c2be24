// Google Benchmark kernels of the model core: odometry integration, covariance propagation and
// ray casting against line maps of growing size.
#include <benchmark/benchmark.h>

#include <vector>

#include "core/diff_drive_odometry.h"
#include "core/line_map.h"
#include "core/rng.h"

namespace locbench::speed {
namespace {

void BM_OdometryStep(benchmark::State& state) {
  Pose2 p;
  const WheelDisplacement u{0.0312, 0.0318};
  for (auto _ : state) {
    p = odometry_step(p, u, 0.198);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_OdometryStep);

void BM_PropagateCovariance(benchmark::State& state) {
  Matrix3 sigma = Matrix3::Identity() * 1e-6;
  const WheelDisplacement u{0.0312, 0.0318};
  for (auto _ : state) {
    sigma = propagate_covariance(sigma, Pose2(0, 0, 0.3), u, 0.198, {1e-4, 1e-4});
    benchmark::DoNotOptimize(sigma);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PropagateCovariance);

// A map of m random segments in a 20 m square; 181 beams cast from the centre.
LineMap random_map(std::size_t m, std::uint64_t seed) {
  Rng rng(seed);
  LineMap map;
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d a(rng.uniform(-10, 10), rng.uniform(-10, 10));
    const double ang = rng.uniform(-kPi, kPi), len = rng.uniform(0.2, 2.0);
    map.segments.push_back({a, a + len * Eigen::Vector2d(std::cos(ang), std::sin(ang))});
  }
  return map;
}

void BM_RayCastScan(benchmark::State& state) {
  const LineMap map = random_map(static_cast<std::size_t>(state.range(0)), 7);
  for (auto _ : state) {
    for (int b = 0; b < 181; ++b) {
      benchmark::DoNotOptimize(map.ray_cast({0.0, 0.0}, deg(b - 90), 30.0));
    }
  }
  state.SetComplexityN(state.range(0));
  state.counters["beams"] =
      benchmark::Counter(181.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RayCastScan)->RangeMultiplier(4)->Range(16, 4096)->Complexity(benchmark::oN);

}  // namespace
}  // namespace locbench::speed

BENCHMARK_MAIN();
