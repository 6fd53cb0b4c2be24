#pragma once
// The scans of a real log's relations, for the scan-pair experiments (laser/real_logs): the scan
// at a relation's stamp, the bearings convention of the Freiburg logs, and one scan's extracted
// lines as a map to match the next scan against.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "baselines/laser/line_extraction.h"
#include "core/line_map.h"
#include "core/log.h"
#include "core/pose2.h"

namespace locbench::experiments {

// A map of the lines extracted from one scan, in its robot frame.
LineMap lines_as_map(const baselines::laser::ExtractionResult& lines);

// The scan stamped t (within 1 ms: mit-csail's relations print 5 decimals, its scans 6), as an
// index into `scans` (stamp → index).
std::optional<std::size_t> scan_near(const std::map<double, std::size_t>& scans, double t);

// A relation of the log whose two stamps have a scan (scan_near) and an odometry pose: the
// relation's index in log.relations, its scans' indices in log.laser, and the odometry's motion
// between them (the correctors' first guess).
struct RelationScanPair {
  std::size_t relation = 0;
  std::size_t first = 0, second = 0;
  Pose2 odometry;
};

// The log's relations spanning at most max_dt [s] that pair two scans inside the odometry's
// span, in the relations' order; the first max_pairs of them (0: all).
std::vector<RelationScanPair> relation_scan_pairs(const Log& log, double max_dt, std::size_t max_pairs = 0);

// "bag": 180-beam scans get the bearings the ROS bags of aces and intel store (angle_min −90°,
// angle_increment 180°/179, so the last beam is at +90°); "log": as read (CARMEN's 1° steps,
// −90°…+89°, or what the log's PARAMs declare).
void apply_beam_angles(Log& log, const std::string& convention);

}  // namespace locbench::experiments
