#include "datasets/sim/laser_model.h"

#include <algorithm>

namespace locbench::sim {

LaserModel::LaserModel(const LaserConfig& c, const LineMap& world, Rng rng)
    : config_(c),
      world_(world),
      rng_(rng),
      bearings_(even_bearings(static_cast<std::size_t>(c.beams), c.first_bearing, c.last_bearing)) {}

std::vector<double> LaserModel::true_ranges(const Pose2& robot) const {
  const Pose2 sensor = robot * config_.mount;
  std::vector<double> r(bearings_.size(), config_.max_range);
  for (std::size_t i = 0; i < bearings_.size(); ++i) {
    if (const auto hit = world_.ray_cast(sensor.translation(), sensor.theta + bearings_[i], config_.max_range)) {
      r[i] = hit->range;
    }
  }
  return r;
}

Scan LaserModel::measure(const Pose2& robot, double timestamp) { return measure_labelled(robot, timestamp).scan; }

LabelledScan LaserModel::measure_labelled(const Pose2& robot, double timestamp) {
  LabelledScan out;
  Scan& s = out.scan;
  s.timestamp = timestamp;
  s.bearings = bearings_;
  s.sensor_pose = config_.mount;
  s.max_range = config_.max_range;
  const double max = config_.max_range;
  const Pose2 sensor = robot * config_.mount;
  s.ranges.assign(bearings_.size(), max);
  out.segment.assign(bearings_.size(), LabelledScan::kNoSegment);
  for (std::size_t i = 0; i < bearings_.size(); ++i) {
    if (const auto hit = world_.ray_cast(sensor.translation(), sensor.theta + bearings_[i], max)) {
      s.ranges[i] = hit->range;
      out.segment[i] = static_cast<int>(hit->segment);
    }
  }
  for (std::size_t i = 0; i < s.ranges.size(); ++i) {
    double& r = s.ranges[i];
    const bool hit = r < max;
    // One uniform draw decides: [0, dropout) drop, [dropout, dropout + spurious) spurious.
    const double u = (config_.dropout > 0.0 || config_.spurious > 0.0) ? rng_.uniform() : 1.0;
    if (u < config_.dropout) {
      r = max;
      out.segment[i] = LabelledScan::kNoSegment;
    } else if (u < config_.dropout + config_.spurious) {
      r = rng_.uniform(0.0, r);
      out.segment[i] = LabelledScan::kNoSegment;
    } else if (hit) {
      double m = config_.range_scale * r + config_.range_offset;
      if (config_.noise > 0.0) m += rng_.normal(0.0, config_.noise);
      r = std::clamp(m, 0.0, max);
      if (r >= max) out.segment[i] = LabelledScan::kNoSegment;
    }
  }
  return out;
}

}  // namespace locbench::sim
