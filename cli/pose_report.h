#pragma once
// The end of the verbs that estimate a pose per scan (`match`, `localize`): the report (printed
// with its summary, written when asked) and the estimated poses in TUM format when asked.
#include <string>

#include "core/trajectory.h"
#include "reports/report.h"

namespace locbench::cli {

// Finishes `report` (reports::finish_report, with the summary printed) and writes `poses` to
// `tum_path` unless it is empty; returns kExitOk.
int finish_pose_report(reports::Report& report, const std::string& verb,
                       const std::string& command_line, const std::string& report_path,
                       const Trajectory& poses, const std::string& tum_path);

}  // namespace locbench::cli
