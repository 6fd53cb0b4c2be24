#pragma once
// The odometry channel: residuals of the nominal odometry model against the reference over
// short windows (motion_windows.h, odometry_model.h), the residual battery, forward selection of
// the catalog's odometry causes (selection.h) with every parameter fitted jointly (a time offset
// profiled over the others), held-out gains per cause in the metric the catalog gives it, and the
// residual structure left after the kept causes.
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

// What a channel hands to the diagnosis; the diagnosis judges the tests once, over all channels.
struct ChannelResult {
  std::vector<ResidualTest> tests;      // the battery on the nominal model
  std::vector<ResidualTest> remaining;  // the battery after the kept causes
  std::vector<Cause> causes;            // every cause tried: detected ones first, in order of entry
  std::vector<ConfoundedGroup> confounded;
  std::vector<Gain> overall_gain;
  // Per cause that passed the likelihood ratio: why it may fail the held-out check (the halves'
  // estimates when they disagree), filled for the diagnosis to use.
  std::vector<std::pair<std::string, std::string>> heldout_notes;
};

struct OdometryChannelResult : ChannelResult {
  OdometryModel nominal_fit;  // the nominal model's noise floor (and dof 0)
  OdometryModel final_fit;    // with every cause that entered
};

OdometryChannelResult diagnose_odometry(const MotionData& d, const DiagnosisOptions& options);

// The held-out split: every third block of `block` windows is held out.
void split_windows(std::size_t n, std::size_t block, std::vector<std::size_t>& train, std::vector<std::size_t>& test);

}  // namespace locbench::diagnosis
