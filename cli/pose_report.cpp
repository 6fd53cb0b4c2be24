#include "cli/pose_report.h"

#include <iostream>

#include "cli/commands.h"
#include "datasets/io/tum_writer.h"
#include "reports/finish_report.h"

namespace locbench::cli {

int finish_pose_report(reports::Report& report, const std::string& verb,
                       const std::string& command_line, const std::string& report_path,
                       const Trajectory& poses, const std::string& tum_path) {
  reports::ReportTail tail(verb, command_line, report_path);
  tail.print_summary = true;
  reports::finish_report(report, tail);
  if (!tum_path.empty()) {
    write_tum(poses, tum_path);
    std::cerr << "wrote " << tum_path << '\n';
  }
  return kExitOk;
}

}  // namespace locbench::cli
