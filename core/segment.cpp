#include "core/segment.h"

#include <algorithm>
#include <cmath>

#include "core/angle.h"

namespace locbench {

LineParams Segment::line() const {
  // Normal of P1P2; orient it so that ρ = n·P1 is non-negative (eq. 5.1).
  const Eigen::Vector2d d = p2 - p1;
  Eigen::Vector2d n(-d.y(), d.x());
  n.normalize();
  double rho = n.dot(p1);
  if (rho < 0.0) {
    n = -n;
    rho = -rho;
  }
  return {rho, wrap_angle(std::atan2(n.y(), n.x()))};
}

double signed_distance_to_line(const LineParams& line, const Eigen::Vector2d& p) {
  return p.x() * std::cos(line.beta) + p.y() * std::sin(line.beta) - line.rho;
}

double distance_to_segment(const Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = s.p2 - s.p1;
  const double len2 = d.squaredNorm();
  if (len2 == 0.0) return (p - s.p1).norm();
  const double t = std::clamp((p - s.p1).dot(d) / len2, 0.0, 1.0);
  return (p - (s.p1 + t * d)).norm();
}

}  // namespace locbench
