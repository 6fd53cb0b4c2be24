#pragma once
// Readers of relative-motion calibration files:
// - stachniss_ls_calib: odom_motions.txt and scanmatched_motions.txt, "dx dy dθ" per line, the
//   same rows in both files (row i of one and row i of the other cover the same interval);
// - grisetti_diffdrive: "tick_left tick_right x y θ" per line, all relative to the previous line.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/calibration_records.h"

namespace locbench::io {

// Reads the two files (plain or gzip) row by row into pairs. '#' comments and blank lines are
// skipped; every other line must hold exactly three finite numbers. Throws InputError naming the
// file and line of a malformed row, and naming both files when their row counts differ.
std::vector<RelativeMotionPair> read_relative_motion_pairs(const std::filesystem::path& odometry_path,
                                                           const std::filesystem::path& reference_path);

// The same for texts in memory; the names stand for the file names in errors.
std::vector<RelativeMotionPair> parse_relative_motion_pairs(std::string_view odometry_text,
                                                            const std::string& odometry_name,
                                                            std::string_view reference_text,
                                                            const std::string& reference_name);

// Reads a tick-motion file (plain or gzip): five finite numbers per line, tick_left tick_right
// x y θ. '#' comments and blank lines are skipped. Throws InputError (file, line, expectation).
std::vector<TickMotion> read_tick_motions(const std::filesystem::path& path);
std::vector<TickMotion> parse_tick_motions(std::string_view text, const std::string& source_name);

}  // namespace locbench::io
