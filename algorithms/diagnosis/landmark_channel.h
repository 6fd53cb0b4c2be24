#pragma once
// The landmark channel: range-bearing observations of surveyed landmarks against TRUEPOS
// (landmark_model.h gives the model). Like the compass channel: the residual battery on the
// nominal model (σ_r, σ_b fitted, everything else nominal), forward selection of the catalog's
// landmark causes by likelihood ratio at α/m (a generic heavy-tail model only after the specific
// causes, as on the odometry channel), each fit by maximum likelihood with 95% intervals
// (ml_fit.h; a time offset profiled, selection.h), the held-out check (every third block of
// `block`·`window_s` seconds held out; primary metric the predictive NLL per observation), and
// the battery again on the final model for what remains.
// `landmark_position_error` is the best landmark of those searched (each with ≥ 10 training
// observations): its threshold divides the level over them too, like the compass disturbance disc.
#include <cstddef>

#include "algorithms/diagnosis/landmark_model.h"
#include "algorithms/diagnosis/odometry_channel.h"

namespace locbench::diagnosis {

struct LandmarkChannelResult : ChannelResult {
  bool testable = false;         // ≥ 40 mapped observations inside the truth's time span
  std::size_t observations = 0;  // mapped observations used
  std::size_t unmapped = 0;      // observations of subjects not in the map, left out
  LandmarkModel nominal_fit;     // σ_r, σ_b fitted, all else nominal
  LandmarkModel final_fit;       // with the detected (held-out validated) causes, σ re-fitted
};

LandmarkChannelResult diagnose_landmarks(const LandmarkData& d, const DiagnosisOptions& options);

// The held-out split in time: observation i is held out when ⌊(t_i − t_0)/block_s⌋ mod 3 = 2.
void split_by_time(const std::vector<LandmarkReading>& readings, double block_s, std::vector<std::size_t>& train,
                   std::vector<std::size_t>& test);

}  // namespace locbench::diagnosis
