#pragma once
// Writer of trajectories in the TUM RGB-D benchmark format: "timestamp x y z qx qy qz qw".
#include <filesystem>
#include <string>

#include "core/trajectory.h"

namespace locbench::io {

// One line per pose: z = 0 and the quaternion of a rotation by θ about z
// (qx = qy = 0, qz = sin(θ/2), qw = cos(θ/2)); numbers in shortest round-trip form; gzip when
// the path ends in ".gz". Throws std::invalid_argument for non-finite values, InputError if it
// cannot write.
void write_tum(const Trajectory& trajectory, const std::filesystem::path& path);

// The same text in memory.
std::string format_tum(const Trajectory& trajectory);

}  // namespace locbench::io
