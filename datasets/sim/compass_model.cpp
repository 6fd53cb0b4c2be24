#include "datasets/sim/compass_model.h"

#include <cmath>

#include "core/angle.h"

namespace locbench::sim {

double quantize(double value, double resolution) {
  if (resolution <= 0.0) return value;
  return std::round(value / resolution) * resolution;
}

double CompassModel::disturbance(const Eigen::Vector2d& p) const {
  double sum = 0.0;
  for (const auto& z : config_.zones) {
    if (z.contains(p)) sum += z.bias;
  }
  return sum;
}

CompassMeasurement CompassModel::measure(const Pose2& truth) {
  CompassMeasurement m;
  m.disturbance = disturbance(truth.translation());
  double h = truth.theta + config_.bias + m.disturbance;
  if (config_.noise > 0.0) h += rng_.normal(0.0, config_.noise);
  // Wrap first so the quantized value stays a multiple of the resolution (which divides 2π).
  // (+ 0.0 turns a quantized −0 into 0.)
  m.heading = wrap_angle(quantize(wrap_angle(h), config_.resolution)) + 0.0;
  return m;
}

}  // namespace locbench::sim
