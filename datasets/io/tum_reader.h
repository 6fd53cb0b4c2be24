#pragma once
// Reader of TUM-format trajectories ("timestamp x y z qx qy qz qw"), projected to the plane.
#include <filesystem>
#include <string>
#include <string_view>

#include "core/trajectory.h"

namespace locbench::io {

// Reads a TUM trajectory (plain or gzip): x, y and the yaw of the quaternion,
// θ = atan2(2(qw qz + qx qy), 1 − 2(qy² + qz²)); z is ignored. '#' comments and blank lines are
// skipped. Throws InputError on malformed lines, a quaternion whose norm is not within 1e-3 of
// 1, or timestamps going backwards.
Trajectory read_tum(const std::filesystem::path& path);

// The same for text in memory; `source_name` stands for the file name in errors.
Trajectory parse_tum(std::string_view text, const std::string& source_name);

}  // namespace locbench::io
