#pragma once
// A 2D map made of line segments, with ray casting against it.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/segment.h"

namespace locbench {

struct RayHit {
  double range = 0.0;       // distance from the ray origin [m]
  std::size_t segment = 0;  // index of the segment hit
};

struct LineMap {
  std::string name;
  std::vector<Segment> segments;

  // First segment hit by the ray origin + t·(cos a, sin a), 0 < t ≤ max_range.
  // Linear in the number of segments; fine for the worlds the simulator uses.
  std::optional<RayHit> ray_cast(const Eigen::Vector2d& origin, double angle, double max_range) const;
};

}  // namespace locbench
