#pragma once
// The motion a log's robot was told to make (or measured itself making), as the simulator's
// replay commands (datasets/sim/scenario.h, motion.kind = "replay"): velocity odometry (ODOM
// poses, or the odometry poses of FLASER records when a log has no ODOM, e.g. mit-csail)
// differenced between consecutive records, or encoder counts (ENCODER, through the log's
// nominal model). For MRCLAM, whose ODOM poses are its commanded v, ω integrated by the midpoint
// rule, the differences give back the logged v, ω.
#include <string>
#include <vector>

#include "core/log.h"
#include "datasets/sim/scenario.h"

namespace locbench::sim {

struct ReplaySource {
  std::vector<ReplayCommand> commands;  // logged times
  std::string odometry;                 // "ODOM" or "ENCODER": what the twin logs
};

// The commands of the odometry records with logged time in [from, to] (all when from > to is
// not the case and the bounds are infinite): command i = (t_i, ΔD/Δt, Δθ/Δt) of the step to
// record i + 1 (ΔD signed along the mid heading), the last one standing still. Records with
// the same time stamp as their predecessor are skipped. Throws InputError (naming the log) when
// the log has neither ENCODER with a nominal model nor odometry poses, or fewer than 2 records
// in the interval.
ReplaySource replay_commands(const Log& log, double from, double to);

}  // namespace locbench::sim
