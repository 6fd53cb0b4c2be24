#include "datasets/sim/simulation_result.h"

#include <algorithm>

namespace locbench::sim {

UmbmarkSummary summarize_umbmark(const std::vector<UmbmarkRun>& runs) {
  UmbmarkSummary s;
  int n_cw = 0, n_ccw = 0;
  for (const auto& r : runs) {
    if (r.direction == Direction::kClockwise) {
      s.centroid_cw += r.error.head<2>();
      ++n_cw;
    } else {
      s.centroid_ccw += r.error.head<2>();
      ++n_ccw;
    }
  }
  if (n_cw > 0) s.centroid_cw /= n_cw;
  if (n_ccw > 0) s.centroid_ccw /= n_ccw;
  s.e_max_syst = std::max(s.centroid_cw.norm(), s.centroid_ccw.norm());
  return s;
}

}  // namespace locbench::sim
