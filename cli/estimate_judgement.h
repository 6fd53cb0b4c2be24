#pragma once
// Estimates are judged before they are printed: a calibration never reports a number
// no robot can have, or an interval no finite data give, as a result.
#include <string>
#include <vector>

#include "reports/report.h"

namespace locbench::cli {

struct EstimateJudgement {
  std::vector<std::string> impossible;    // "wheelbase = -17.4: a length or scale must be > 0": exit 1
  std::vector<std::string> unidentified;  // names newly marked "not identifiable" (with a note)
};

// Judges every estimate (`over` = "estimate") of `out` and marks those the data do not determine
// identifiable = false, with the reason in its note:
//   - a value that is not finite is impossible, and is removed from the results (JSON has no NaN);
//   - a parameter that is a length or a scale (wheelbase, b, B, r_L, r_R, D_L, D_R, c_L, c_R,
//     left_scale, right_scale, tv_scale, rv_scale, E_d, E_b, E_o) is impossible at ≤ 0 or > 1000
//     (a scale factor also below 1/1000);
//     when its 95% interval reaches ≤ 0 the data do not determine it (not even its sign);
//   - with `zero_width_unidentified`, a zero standard error (an interval of width 0, which no
//     finite data give) means the data do not determine it either.
EstimateJudgement judge_estimates(reports::ExperimentResults& out, bool zero_width_unidentified);

}  // namespace locbench::cli
