#pragma once
// Reads one laser scan stored as JSON (plain or gzip): {"ranges": [r0, r1, …] [m],
// "bearings": [b0, b1, …] [rad]} — the laser_line_extraction test data in
// ../shared/datasets/laser_scans. "bearings" may be replaced by "angle_min" and
// "angle_increment" (ROS LaserScan style); "range_max" is optional (default: no limit).
#include <filesystem>

#include "core/scan.h"

namespace locbench::io {

// InputError naming the file and what was expected for malformed JSON, a missing or non-numeric
// field, or bearings and ranges of different lengths.
Scan read_scan_json(const std::filesystem::path& path);

}  // namespace locbench::io
