#pragma once
// Odometry and ground-truth poses of a log at arbitrary times, by interpolation.
#include <optional>

#include "core/log.h"
#include "core/pose2.h"
#include "core/trajectory.h"

namespace locbench::io {

// The odometry trajectory of a log: its ODOM poses; for a log without ODOM records (e.g.
// mit-csail) the odom poses logged with its FLASER scans.
Trajectory odometry_trajectory(const Log& log);

// Odometry pose at time t: position linear in time, heading along the shorter arc, between the
// records of odometry_trajectory(log) around t; nullopt outside their time span. O(log n).
std::optional<Pose2> interpolate_odometry(const Log& log, double t);

// Ground-truth (TRUEPOS / Vicon) pose at time t, interpolated the same way.
std::optional<Pose2> interpolate_truth(const Log& log, double t);

}  // namespace locbench::io
