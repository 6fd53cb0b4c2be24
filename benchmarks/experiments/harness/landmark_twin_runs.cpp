#include "benchmarks/experiments/harness/landmark_twin_runs.h"

#include <cmath>
#include <limits>

#include "core/rng.h"
#include "core/statistics.h"

namespace locbench::experiments::landmarks {
namespace {

constexpr double kHorizons[] = {1.0, 10.0, 60.0};
const char* const kHorizonNames[] = {"rpe_1s", "rpe_10s", "rpe_60s"};

// Every metric of one run of the methods on one part (a real part or a twin).
struct RunMetrics {
  std::map<std::string, std::vector<double>> per_method;  // metric → one value per method
  std::map<std::string, double> dead_reckoning;           // metric → value
};

RunMetrics run_metrics(const TrackingData& data, const std::vector<TrackResult>& results, const FamilyOptions& family) {
  RunMetrics m;
  for (const TrackResult& r : results) {
    m.per_method["position_rmse"].push_back(r.position_rmse());
    m.per_method["heading_rmse"].push_back(r.heading_rmse());
    m.per_method["nees"].push_back(r.nees.empty() ? std::numeric_limits<double>::infinity() : mean(r.nees));
    m.per_method["gated_fraction"].push_back(r.gated_fraction());
  }
  m.dead_reckoning["dead_reckoning_rmse"] = dead_reckoning(data, family.gate).position_rmse();
  for (std::size_t h = 0; h < std::size(kHorizons); ++h)
    m.dead_reckoning[kHorizonNames[h]] = odometry_rpe(data, kHorizons[h]);
  return m;
}

}  // namespace

double odometry_rpe(const TrackingData& data, double horizon_s) {
  const diagnosis::MotionData& d = data.motion;
  if (d.windows.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> lengths;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < d.windows.size(); ++i) {
    lengths.push_back(d.windows[i].t1 - d.windows[i].t0);
    index.push_back(i);
  }
  const double typical = quantile(lengths, 0.5);
  const auto chain = static_cast<std::size_t>(std::max(1.0, std::round(horizon_s / typical)));
  const diagnosis::RelativePoseError e = diagnosis::relative_pose_error(d, diagnosis::OdometryModel{}, index, chain);
  return e.segments > 0 ? e.translation_rms : std::numeric_limits<double>::quiet_NaN();
}

PredictivityCells twin_predictions(const TrackingData& test, const std::vector<MethodScore>& tuned,
                                   const FilterModels& models, const FamilyOptions& family,
                                   const TwinRunOptions& options, const MotionNoiseStructure& extended_structure) {
  std::vector<TrackResult> real_results;
  for (const MethodScore& m : tuned) real_results.push_back(m.heldout);
  const RunMetrics real = run_metrics(test, real_results, family);

  // twin j (0 nominal, 1 extended) → its runs' metrics
  std::vector<RunMetrics> runs[2];
  for (int j = 0; j < 2; ++j) {
    const diagnosis::OdometryModel& motion = j == 0 ? models.nominal_motion : models.diagnosed_motion;
    const LandmarkSensorModel& sensor = j == 0 ? models.nominal_sensor : models.diagnosed_sensor;
    for (int k = 0; k < options.runs; ++k) {
      const TrackingData twin = landmark_twin(test, motion, sensor, Rng::derive_seed(options.seed, 2 * k + j),
                                              j == 0 ? MotionNoiseStructure{} : extended_structure);
      runs[j].push_back(run_metrics(twin, run_tuned(twin, tuned, models, family), family));
    }
  }
  const auto interval = [&](int j, auto&& value) {
    std::vector<double> v;
    for (const RunMetrics& r : runs[j]) v.push_back(value(r));
    return predictive_interval(v);
  };
  PredictivityCells cells;
  for (const auto& [metric, values] : real.per_method) {
    for (std::size_t i = 0; i < tuned.size(); ++i) {
      PredictivityCell c;
      c.log = test.log;
      c.method = to_string(tuned[i].method);
      c.real = values[i];
      c.real_diverged = tuned[i].heldout.diverged;
      c.nominal = interval(0, [&](const RunMetrics& r) { return r.per_method.at(metric)[i]; });
      c.extended = interval(1, [&](const RunMetrics& r) { return r.per_method.at(metric)[i]; });
      cells[metric].push_back(c);
    }
  }
  for (const auto& [metric, value] : real.dead_reckoning) {
    PredictivityCell c;
    c.log = test.log;
    c.method = "dead_reckoning";
    c.real = value;
    c.nominal = interval(0, [&](const RunMetrics& r) { return r.dead_reckoning.at(metric); });
    c.extended = interval(1, [&](const RunMetrics& r) { return r.dead_reckoning.at(metric); });
    cells[metric].push_back(c);
  }
  return cells;
}

}  // namespace locbench::experiments::landmarks
