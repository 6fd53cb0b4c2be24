#pragma once
// The two ends of the verbs that estimate a pose per scan (`match`, `localize`): the log they
// read, and the report (printed with its summary, written when asked) and the estimated poses in
// TUM format when asked.
#include <string>

#include "core/trajectory.h"
#include "datasets/catalog/log_spec.h"
#include "reports/report.h"

namespace locbench::cli {

// The log `spec` (a catalog name or a file: datasets/catalog/log_spec.h) with its dataset record,
// named after the log; it must hold laser scans, each with at most limits::kBeamsPerScan beams,
// otherwise InputError naming the log.
catalog::LoadedLog load_scan_log(const std::string& spec);

// Finishes `report` (reports::finish_report, with the summary printed) and writes `poses` to
// `tum_path` unless it is empty; returns kExitOk.
int finish_pose_report(reports::Report& report, const std::string& verb, const std::string& command_line,
                       const std::string& report_path, const Trajectory& poses, const std::string& tum_path);

}  // namespace locbench::cli
