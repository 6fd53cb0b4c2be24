#include "datasets/sim/simulation_result.h"

#include <algorithm>
#include <stdexcept>

#include "core/dead_reckoning.h"
#include "datasets/sim/umbmark_input.h"

namespace locbench::sim {

UmbmarkSummary summarize_umbmark(const std::vector<UmbmarkRun>& runs) {
  const UmbmarkCentroids c = umbmark_centroids(umbmark_returns(runs));
  return {c.cw, c.ccw, c.e_max_syst};
}

Trajectory true_trajectory(const SimulationResult& result) {
  Trajectory t;
  for (const TrajectoryPoint& p : result.trajectory) t.push_back({p.t, p.pose});
  return t;
}

Pose2 dead_reckoning_end_error(const SimulationResult& r) {
  const auto model = r.log.nominal_model();
  if (!model || r.log.encoders.empty() || r.trajectory.empty()) {
    throw std::logic_error("dead_reckoning_end_error: run without encoders or nominal model");
  }
  const Trajectory truth = true_trajectory(r);
  const auto start = truth.pose_at(r.log.encoders.front().t);
  if (!start) throw std::logic_error("dead_reckoning_end_error: first encoder sample outside the truth");
  const Trajectory odo = dead_reckon_encoders(r.log.encoders, *model, *start);
  // The last ENCODER record may be logged a few ms after the last true pose sample.
  const double t_end = std::min(odo.end_time(), truth.end_time());
  return between(*truth.pose_at(t_end), *odo.pose_at(t_end));
}

}  // namespace locbench::sim
