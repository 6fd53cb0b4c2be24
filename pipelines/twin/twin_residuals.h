#pragma once
// The nominal model's window residuals of a log (reference − nominal odometry prediction, x along
// and y left of the window's start heading, θ; algorithms/diagnosis/odometry_model.h), and the
// same windows read against a twin's simulated reference: what the twins are compared on. The
// twin replays the log's odometry, so one set of windows (the log's) serves all three, and the
// samples compared cover exactly the same stretches of the log.
#include <array>
#include <vector>

#include "algorithms/diagnosis/motion_windows.h"
#include "core/log.h"

namespace locbench::sim {

// The log's windows of about `window_s` seconds (relations: one per relation of ≤ 10 s, whatever
// its span). Throws InputError (from the diagnosis's window builder) for logs without odometry
// or reference, or with fewer than `min_windows` windows.
diagnosis::MotionData residual_windows(const Log& log, double window_s, std::size_t min_windows = 5);

// Residual of every window of `d` against its own reference; NaN for windows the reference does
// not cover.
std::vector<std::array<double, 3>> nominal_residuals(const diagnosis::MotionData& d);

// Residual of every window of `d` against the TRUEPOS of `twin` (twin time + time_origin =
// logged time) instead of the log's reference; NaN where the twin's truth does not cover a window.
std::vector<std::array<double, 3>> twin_residuals(const diagnosis::MotionData& d, const Log& twin, double time_origin);

// Component c (0 = x, 1 = y, 2 = θ) of the windows finite in every one of `sets`, for each set.
std::vector<std::vector<double>> common_component(const std::vector<const std::vector<std::array<double, 3>>*>& sets,
                                                  int c);

}  // namespace locbench::sim
