#include "datasets/sim/simulation_result.h"

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

}  // namespace locbench::sim
