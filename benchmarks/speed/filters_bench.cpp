// Google Benchmark kernels of the chapter-4 filters: one predict + compass update step of each
// 3-state EKF (target: at most 1 µs per step in Release). Each iteration runs a fresh filter
// over the same 256 synthetic corridor samples (straight 62.5 mm per sample with wheel noise, a
// noisy compass), so the filters stay in their normal regime; "step" is the time per sample.
#include <benchmark/benchmark.h>

#include <optional>
#include <vector>

#include "algorithms/filters/compass_ekf.h"
#include "algorithms/filters/quantization_noise.h"
#include "baselines/filters/fixed_q_ekf.h"
#include "baselines/filters/sage_husa_aekf.h"
#include "baselines/filters/vb_akf.h"
#include "core/rng.h"

namespace locbench::speed {
using locbench::baselines::filters::FixedQEkf, locbench::baselines::filters::FixedQEkfOptions,
    locbench::baselines::filters::SageHusaAekf, locbench::baselines::filters::SageHusaOptions,
    locbench::baselines::filters::VbAkf, locbench::baselines::filters::VbAkfOptions;
using locbench::filters::CompassEkf, locbench::filters::CompassEkfOptions, locbench::filters::l2_optimal_sigma,
    locbench::filters::OdometryNoiseForm;
namespace {

constexpr double kWheelbase = 0.19793;
constexpr int kSamples = 256;

struct Sample {
  WheelDisplacement u;
  std::optional<double> compass;
};

const std::vector<Sample>& samples() {
  static const std::vector<Sample> s = [] {
    Rng rng(42);
    std::vector<Sample> v;
    double heading = 0.0;
    for (int k = 0; k < kSamples; ++k) {
      const WheelDisplacement u{0.0625 + 0.0012 * rng.normal(), 0.0625 + 0.0012 * rng.normal()};
      heading += (u.right - u.left) / kWheelbase;
      v.push_back({u, heading + deg(1.0) * rng.normal()});
    }
    return v;
  }();
  return s;
}

template <class Make>
void run_filter(benchmark::State& state, Make make) {
  const auto& in = samples();
  for (auto _ : state) {
    auto filter = make();
    for (const Sample& s : in) benchmark::DoNotOptimize(filter.step(s.u, s.compass));
  }
  state.SetItemsProcessed(state.iterations() * kSamples);
  state.counters["step"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSamples,
                                              benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_CompassEkfAdaptiveStep(benchmark::State& state) {
  run_filter(state, [] { return CompassEkf(CompassEkfOptions{}, kWheelbase, Pose2()); });
}
BENCHMARK(BM_CompassEkfAdaptiveStep);

void BM_CompassEkfJacobianNoiseStep(benchmark::State& state) {
  CompassEkfOptions o;
  o.noise.form = OdometryNoiseForm::kJacobian;
  run_filter(state, [&] { return CompassEkf(o, kWheelbase, Pose2()); });
}
BENCHMARK(BM_CompassEkfJacobianNoiseStep);

void BM_FixedQEkfStep(benchmark::State& state) {
  run_filter(state, [] { return FixedQEkf(FixedQEkfOptions{}, kWheelbase, Pose2()); });
}
BENCHMARK(BM_FixedQEkfStep);

void BM_SageHusaAekfStep(benchmark::State& state) {
  run_filter(state, [] { return SageHusaAekf(SageHusaOptions{}, kWheelbase, Pose2()); });
}
BENCHMARK(BM_SageHusaAekfStep);

void BM_VbAkfStep(benchmark::State& state) {
  run_filter(state, [] { return VbAkf(VbAkfOptions{}, kWheelbase, Pose2()); });
}
BENCHMARK(BM_VbAkfStep);

// The exact L2-optimal quantization σ (Brent on the closed-form G₂).
void BM_L2OptimalSigma(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(l2_optimal_sigma(12.64));
}
BENCHMARK(BM_L2OptimalSigma);

}  // namespace
}  // namespace locbench::speed
