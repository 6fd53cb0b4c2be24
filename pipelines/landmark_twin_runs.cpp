#include "pipelines/landmark_twin_runs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/rng.h"
#include "core/statistics.h"
#include "experiment_framework/parallel_tasks.h"

namespace locbench::experiments::landmarks {
namespace {

constexpr double kHorizons[] = {1.0, 10.0, 60.0};
const char* const kHorizonNames[] = {"rpe_1s", "rpe_10s", "rpe_60s"};

// Every metric of one run of the methods on one part (a real part or a twin).
struct RunMetrics {
  std::map<std::string, std::vector<double>> per_method;  // metric → one value per method
  std::map<std::string, double> dead_reckoning;           // metric → value
  std::array<std::vector<double>, 3> residuals;           // 1 s window residuals x, y, θ (time order)
};

std::array<std::vector<double>, 3> window_residuals(const TrackingData& data) {
  std::array<std::vector<double>, 3> out;
  for (const diagnosis::MotionWindow& w : data.motion.windows) {
    const diagnosis::WindowResidual r = diagnosis::window_residual(data.motion, w, diagnosis::OdometryModel{});
    if (!r.valid || r.heading_only) continue;
    for (int c = 0; c < 3; ++c) out[c].push_back(r.r(c));
  }
  return out;
}

// The filter metrics of one run of the methods: metric → one value per method.
std::map<std::string, std::vector<double>> filter_metrics(const std::vector<TrackResult>& results) {
  std::map<std::string, std::vector<double>> per_method;
  for (const TrackResult& r : results) {
    per_method["position_rmse"].push_back(r.position_rmse());
    per_method["heading_rmse"].push_back(r.heading_rmse());
    per_method["nees"].push_back(r.nees.empty() ? std::numeric_limits<double>::infinity() : mean(r.nees));
    per_method["gated_fraction"].push_back(r.gated_fraction());
  }
  return per_method;
}

RunMetrics run_metrics(const TrackingData& data, const std::vector<TrackResult>& results, const FamilyOptions& family) {
  RunMetrics m;
  m.per_method = filter_metrics(results);
  m.dead_reckoning["dead_reckoning_rmse"] = dead_reckoning(data, family.gate).position_rmse();
  for (std::size_t h = 0; h < std::size(kHorizons); ++h)
    m.dead_reckoning[kHorizonNames[h]] = odometry_rpe(data, kHorizons[h]);
  m.residuals = window_residuals(data);
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

TwinForecast twin_predictions(const TrackingData& test, const std::vector<MethodScore>& tuned,
                              const FilterModels& models, const FamilyOptions& family, const TwinRunOptions& options) {
  std::vector<TrackResult> real_results;
  for (const MethodScore& m : tuned) real_results.push_back(m.heldout);
  const RunMetrics real = run_metrics(test, real_results, family);

  // twin j (0 nominal, 1 extended, 2 the sensor twin) → its runs' metrics
  std::vector<RunMetrics> runs[3];
  const auto per_twin = static_cast<std::size_t>(std::max(options.runs, 0));
  for (std::vector<RunMetrics>& r : runs) r.resize(per_twin);
  experiments::parallel_tasks(options.threads, 3 * per_twin, [&](std::size_t task) {
    const int j = static_cast<int>(task / per_twin), k = static_cast<int>(task % per_twin);
    const TrackingData twin =
        j == 2
            ? landmark_sensor_twin(test, models.diagnosed_sensor, Rng::derive_seed(options.seed, 2 * per_twin + k))
            : landmark_twin(test, j == 0 ? models.nominal_motion : models.diagnosed_motion,
                            j == 0 ? models.nominal_sensor : models.diagnosed_sensor,
                            Rng::derive_seed(options.seed, 2 * k + j),
                            j == 0 ? MotionNoiseStructure{} : models.diagnosed_motion_structure, options.follow_time_s);
    // The sensor twin's odometry is the log's: its dead reckoning and window residuals are the
    // real ones, not computed again.
    runs[j][static_cast<std::size_t>(k)] =
        j == 2 ? RunMetrics{filter_metrics(run_tuned(twin, tuned, models, family)), {}, {}}
               : run_metrics(twin, run_tuned(twin, tuned, models, family), family);
  });
  const auto interval = [&](int j, auto&& value) {
    std::vector<double> v;
    for (const RunMetrics& r : runs[j]) v.push_back(value(r));
    return predictive_interval(v);
  };
  TwinForecast forecast;
  PredictivityCells& cells = forecast.cells;
  for (const auto& [metric, values] : real.per_method) {
    for (std::size_t i = 0; i < tuned.size(); ++i) {
      PredictivityCell c;
      c.log = test.log;
      c.method = to_string(tuned[i].method);
      c.real = values[i];
      c.real_diverged = tuned[i].heldout.diverged;
      c.nominal = interval(0, [&, &m = metric](const RunMetrics& r) { return r.per_method.at(m)[i]; });
      c.extended = interval(1, [&, &m = metric](const RunMetrics& r) { return r.per_method.at(m)[i]; });
      c.sensor = interval(2, [&, &m = metric](const RunMetrics& r) { return r.per_method.at(m)[i]; });
      cells[metric].push_back(c);
    }
  }
  for (const auto& [metric, value] : real.dead_reckoning) {
    PredictivityCell c;
    c.log = test.log;
    c.method = "dead_reckoning";
    c.real = value;
    c.nominal = interval(0, [&m = metric](const RunMetrics& r) { return r.dead_reckoning.at(m); });
    c.extended = interval(1, [&m = metric](const RunMetrics& r) { return r.dead_reckoning.at(m); });
    cells[metric].push_back(c);
  }
  Rng rng(Rng::derive_seed(options.seed, 1u << 20));
  const char* const components[] = {"x", "y", "theta"};
  for (int c = 0; c < 3; ++c) {
    ResidualKs k;
    k.log = test.log;
    k.component = components[c];
    for (int j = 0; j < 2; ++j) {
      std::vector<std::vector<double>> twin_runs;
      for (const RunMetrics& r : runs[j]) twin_runs.push_back(r.residuals[c]);
      (j == 0 ? k.nominal : k.extended) =
          ks_block_bootstrap(real.residuals[c], twin_runs, kKsBlockWindows, kKsResamples, rng);
    }
    forecast.residuals.push_back(std::move(k));
  }
  return forecast;
}

}  // namespace locbench::experiments::landmarks
