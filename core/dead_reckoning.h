#pragma once
// Dead reckoning: integrate encoder counts or logged velocities into a trajectory.
#include <span>

#include "core/robot_params.h"
#include "core/sensor_data.h"
#include "core/trajectory.h"

namespace locbench {

// Integrates cumulative encoder counts with a wheel model (eq. 1.1–1.3), starting at `start`
// at the time of the first reading.
Trajectory dead_reckon_encoders(std::span<const EncoderReading> encoders, const NominalModel& model,
                                const Pose2& start);

// Integrates forward and rotational velocities (tv, rv held over each interval, midpoint
// rule), starting at `start` at the time of the first reading.
Trajectory dead_reckon_velocities(std::span<const OdometryReading> odometry, const Pose2& start);

}  // namespace locbench
