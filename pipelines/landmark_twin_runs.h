#pragma once
// The predictivity cells of one landmark log: the real held-out result of every tuned
// method and of dead reckoning, beside the results of seeded twins (landmark_twin.h) of the
// held-out part under the nominal models (the fitted white floor, the nominal sensor) and under
// the diagnosed ones (every kept cause, the fitted landmark sensor), and of sensor twins
// (landmark_sensor_twin: the part's own odometry and truth, the observations drawn from the fitted
// landmark sensor), which tell a miss of the motion model from one of the sensor model. Every twin run uses the
// methods' settings tuned on the real tuning part — the twin forecasts what the user will see.
//
// Metrics (one list of cells each; predictivity.h): for each filter method "position_rmse" [m],
// "heading_rmse" [rad], "nees" (time average) and "gated_fraction" (a method's cells are left out
// of the correlations where its real run diverged); for dead reckoning
// "dead_reckoning_rmse" [m] and the relative pose error of the logged odometry over 1 s, 10 s and
// 60 s ("rpe_1s", "rpe_10s", "rpe_60s" [m]: RMS translation error of non-overlapping chains of
// diagnosis windows, diagnosis::relative_pose_error).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/two_sample_ks.h"
#include "pipelines/filter_models.h"
#include "pipelines/landmark_family.h"
#include "pipelines/landmark_twin.h"
#include "pipelines/predictivity.h"

namespace locbench::experiments::landmarks {

struct TwinRunOptions {
  int runs = 20;           // seeded runs of each twin
  std::uint64_t seed = 1;  // run k of twin j (0 nominal, 1 extended) has seed Rng::derive_seed(seed, 2k + j), of
                           // the sensor twin Rng::derive_seed(seed, 2·runs + k)
  int threads = 1;         // the runs side by side (experiments::parallel_tasks); same results for any number
  // The nominal and extended twins steer toward the log's path with this time constant [s]
  // (landmark_twin; 0: open-loop replay of the logged commands).
  double follow_time_s = 40.0;
};

using PredictivityCells = std::map<std::string, std::vector<PredictivityCell>>;  // by metric

// How the part's 1 s window residuals (the logged odometry under the nominal model against the
// truth; x along, y left, θ) compare with each twin's, pooled over its runs: the KS distance with a
// block-bootstrap p-value (core/two_sample_ks.h; blocks of kKsBlockWindows windows, so the
// neighbours' correlation is kept). p > 0.05: the twin's residuals are not distinguishable.
inline constexpr std::size_t kKsBlockWindows = 10;
inline constexpr int kKsResamples = 200;
struct ResidualKs {
  std::string log, component;  // "x", "y", "theta"
  KsBootstrap nominal, extended;
};

struct TwinForecast {
  PredictivityCells cells;
  std::vector<ResidualKs> residuals;  // one per component
};

// `tuned` holds the real held-out results (MethodScore::heldout) on `test`; the extended twin's
// window residuals are correlated in time by models.diagnosed_motion_structure (the nominal
// twin's are white).
TwinForecast twin_predictions(const TrackingData& test, const std::vector<MethodScore>& tuned,
                              const FilterModels& models, const FamilyOptions& family, const TwinRunOptions& options);

// The RMS relative pose error of the logged odometry against the data's truth over chains of
// windows `horizon_s` long [m] (NaN when no chain fits).
double odometry_rpe(const TrackingData& data, double horizon_s);

}  // namespace locbench::experiments::landmarks
