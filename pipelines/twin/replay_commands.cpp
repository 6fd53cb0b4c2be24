#include "pipelines/twin/replay_commands.h"

#include <cmath>

#include "core/angle.h"
#include "core/errors.h"
#include "datasets/io/odometry_interpolation.h"

namespace locbench::sim {
using io::odometry_trajectory;
namespace {

struct Step {
  double t = 0.0, distance = 0.0, rotation = 0.0;  // record time; motion to the next record
};

std::vector<ReplayCommand> to_commands(const std::vector<double>& t, const std::vector<Step>& steps) {
  std::vector<ReplayCommand> out;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double dt = t[i + 1] - t[i];
    out.push_back({t[i], steps[i].distance / dt, steps[i].rotation / dt});
  }
  if (!t.empty()) out.push_back({t.back(), 0.0, 0.0});
  return out;
}

}  // namespace

ReplaySource replay_commands(const Log& log, double from, double to) {
  ReplaySource src;
  std::vector<double> times;
  std::vector<Step> steps;
  const auto inside = [&](double t) { return t >= from && t <= to; };
  if (!log.encoders.empty()) {
    const auto model = log.nominal_model();
    if (!model) {
      throw InputError(log.source.empty() ? log.name : log.source, 0,
                       "ENCODER records need the PARAM nominal model (robot_meters_per_tick_left/right, "
                       "robot_wheelbase) to be replayed");
    }
    src.odometry = "ENCODER";
    const EncoderReading* prev = nullptr;
    for (const auto& e : log.encoders) {
      if (!inside(e.t) || (prev && e.t <= prev->t)) continue;
      if (prev) {
        const double ul = model->meters_per_tick_left * static_cast<double>(e.left - prev->left);
        const double ur = model->meters_per_tick_right * static_cast<double>(e.right - prev->right);
        steps.push_back({prev->t, 0.5 * (ul + ur), (ur - ul) / model->wheelbase});
      }
      times.push_back(e.t);
      prev = &e;
    }
  } else {
    src.odometry = "ODOM";
    const Trajectory odo = odometry_trajectory(log);
    const StampedPose* prev = nullptr;
    for (const auto& p : odo.poses()) {
      if (!inside(p.t) || (prev && p.t <= prev->t)) continue;
      if (prev) {
        const double dth = angle_diff(p.pose.theta, prev->pose.theta);
        const double mid = prev->pose.theta + 0.5 * dth;
        const double dx = p.pose.x - prev->pose.x, dy = p.pose.y - prev->pose.y;
        double d = std::hypot(dx, dy);
        if (dx * std::cos(mid) + dy * std::sin(mid) < 0.0) d = -d;
        steps.push_back({prev->t, d, dth});
      }
      times.push_back(p.t);
      prev = &p;
    }
  }
  if (times.size() < 2) {
    throw InputError(log.source.empty() ? log.name : log.source, 0,
                     "fewer than 2 odometry records (ENCODER, ODOM or FLASER odometry poses) to replay in the "
                     "chosen interval");
  }
  src.commands = to_commands(times, steps);
  return src;
}

}  // namespace locbench::sim
