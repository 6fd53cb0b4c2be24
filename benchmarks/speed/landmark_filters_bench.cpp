// Google Benchmark kernel of the landmark filter family on logged data: every method of
// noise/landmark_logs (7 methods × 42 tuning runs on the first half + 1 held-out run on the second)
// on the five MRCLAM Dataset 6 robots, read from $LOCBENCH_DATA (skipped with a message when
// absent). The models are the nominal ones with a fixed floor, so the diagnosis (its own cost) is
// outside; the diagnosed model's filter carries correlated sensor and motion noise, as in the
// experiment (the 8-state filter). The time per iteration is the whole family on all five robots
// (goal: ≤ 10 s of CPU).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "datasets/catalog/data_root.h"
#include "datasets/catalog/dataset_catalog.h"
#include "pipelines/landmark_family.h"

namespace locbench::speed {
namespace {
using namespace locbench::experiments::landmarks;
using catalog::find_dataset, catalog::load_catalog_dataset;

struct Halves {
  TrackingData train, test;
};

const std::vector<Halves>* robots() {
  static const std::vector<Halves> halves = [] {
    std::vector<Halves> v;
    try {
      for (int r = 1; r <= 5; ++r) {
        const auto* e = find_dataset("mrclam6_robot" + std::to_string(r));
        if (!e || !std::filesystem::exists(catalog::data_root() / e->path.substr(0, e->path.find('#')))) return v;
        const Log log = load_catalog_dataset(*e, catalog::data_root());
        const double from = std::max(log.odometry.front().t, log.truth.front().t);
        const double to = std::min(log.odometry.back().t, log.truth.back().t);
        const double mid = 0.5 * (from + to);
        v.push_back({tracking_data(log, from, mid, 0.26), tracking_data(log, mid, to, 0.26)});
      }
    } catch (const std::exception&) {
      v.clear();
    }
    return v;
  }();
  return halves.size() == 5 ? &halves : nullptr;
}

void BM_LandmarkFilterFamily_mrclam6(benchmark::State& state) {
  const auto* data = robots();
  if (!data) {
    state.SkipWithError(
        ("MRCLAM Dataset 6 not found under " + catalog::data_root().string() + " (set LOCBENCH_DATA)").c_str());
    return;
  }
  FilterModels models;
  models.nominal_motion.sigma_x = models.nominal_motion.sigma_y = 0.02;
  models.nominal_motion.sigma_theta = 0.02;
  models.diagnosed_motion = models.nominal_motion;
  const NoiseCorrelation half{0.5, 5.0};  // Dataset 6's shares and times are 5–100%, 0.4–30 s
  models.diagnosed_motion_structure.x = models.diagnosed_motion_structure.y = half;
  models.diagnosed_motion_structure.theta = half;
  models.diagnosed_sensor.structure.range_correlation = half;
  models.diagnosed_sensor.structure.bearing_correlation = half;
  const FamilyOptions options;
  std::size_t runs = 0;
  for (auto _ : state) {
    for (const Halves& h : *data) {
      const auto scores = tune_and_score(h.train, h.test, models, options);
      for (const auto& s : scores) runs += s.grid_runs + 1;
      benchmark::DoNotOptimize(scores.data());
    }
  }
  state.counters["filter_runs"] = static_cast<double>(runs) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_LandmarkFilterFamily_mrclam6)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace locbench::speed
