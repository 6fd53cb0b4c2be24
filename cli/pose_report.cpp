#include "cli/pose_report.h"

#include <fmt/format.h>

#include <iostream>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "datasets/catalog/data_root.h"
#include "datasets/io/tum_writer.h"
#include "reports/finish_report.h"

namespace locbench::cli {
using io::write_tum;

catalog::LoadedLog load_scan_log(const std::string& spec) {
  catalog::LogSpec what;
  what.log = spec;
  catalog::LoadedLog loaded = catalog::load_log_spec(what, catalog::data_root());
  loaded.dataset.name = loaded.log.name.empty() ? "log" : loaded.log.name;
  const Log& log = loaded.log;
  if (log.laser.empty()) {
    throw InputError(spec, 0, "laser scans (FLASER/ROBOTLASER records); the log has none");
  }
  double ranges = 0.0;
  for (const LaserReading& reading : log.laser) {
    limits::check(static_cast<double>(reading.scan.ranges.size()), limits::kBeamsPerScan, spec,
                  fmt::format("the scan at t = {} (its beams)", reading.scan.timestamp));
    ranges += static_cast<double>(reading.scan.ranges.size());
  }
  limits::check(ranges, limits::kLaserRangesPerLog, spec, fmt::format("laser ranges ({} scans)", log.laser.size()));
  return loaded;
}

int finish_pose_report(reports::Report& report, const std::string& verb, const std::string& command_line,
                       const std::string& report_path, const Trajectory& poses, const std::string& tum_path) {
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
