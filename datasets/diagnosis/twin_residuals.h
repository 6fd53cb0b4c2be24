#pragma once
// The nominal model's window residuals of a log (reference − nominal odometry prediction, x along
// and y left of the window's start heading, θ; algorithms/diagnosis/odometry_model.h), and the
// pairing of two logs' windows by time: what the twins are compared on.
#include <array>
#include <string>
#include <vector>

#include "datasets/log/log.h"

namespace locbench::sim {

struct WindowResiduals {
  std::vector<double> t0, t1;             // window ends [s], logged time + shift
  std::vector<std::array<double, 3>> r;   // x [m], y [m], θ [rad]
  std::string reference;                  // "truepos" or "relations"
};

// Windows of about `window_s` seconds (relations: one per relation, whatever its span); times
// shifted by `time_shift` (twin time → logged time). Throws InputError (from the diagnosis's
// window builder) for logs without odometry or reference, or with fewer than `min_windows`.
WindowResiduals nominal_residuals(const Log& log, double window_s, double time_shift = 0.0,
                                  std::size_t min_windows = 5);

// Index pairs (i in a, j in b) of windows with the same ends within `tolerance` seconds.
std::vector<std::pair<std::size_t, std::size_t>> pair_windows(const WindowResiduals& a, const WindowResiduals& b,
                                                              double tolerance = 2e-3);

// Component c (0 = x, 1 = y, 2 = θ) of the windows `index` selects (first or second of pairs).
std::vector<double> component(const WindowResiduals& w, int c,
                              const std::vector<std::pair<std::size_t, std::size_t>>& pairs, bool first);

}  // namespace locbench::sim
