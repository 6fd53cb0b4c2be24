#include "core/line_map.h"

#include <cmath>

namespace locbench {

std::optional<RayHit> LineMap::ray_cast(const Eigen::Vector2d& origin, double angle, double max_range) const {
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  std::optional<RayHit> best;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Eigen::Vector2d e = segments[i].p2 - segments[i].p1;
    const double denom = dir.x() * e.y() - dir.y() * e.x();  // cross(dir, e)
    if (std::abs(denom) < 1e-12) continue;                   // parallel: no single hit
    const Eigen::Vector2d w = segments[i].p1 - origin;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denom;      // along the ray
    const double u = (w.x() * dir.y() - w.y() * dir.x()) / denom;  // along the segment
    if (t <= 1e-9 || t > max_range || u < 0.0 || u > 1.0) continue;
    if (!best || t < best->range) best = RayHit{t, i};
  }
  return best;
}

}  // namespace locbench
