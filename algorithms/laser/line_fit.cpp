#include "algorithms/laser/line_fit.h"

#include <cmath>

#include "core/angle.h"

namespace locbench::laser {

LineFit fit_line(std::span<const Eigen::Vector2d> points) {
  LineFit f;
  f.count = points.size();
  if (points.empty()) return f;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : points) c += p;
  c /= static_cast<double>(points.size());
  double sxx = 0, syy = 0, sxy = 0;
  for (const auto& p : points) {
    const Eigen::Vector2d d = p - c;
    sxx += d.x() * d.x();
    syy += d.y() * d.y();
    sxy += d.x() * d.y();
  }
  // Direction of largest spread: angle φ with tan 2φ = 2sxy / (sxx − syy).
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  f.centroid = c;
  f.direction = {std::cos(phi), std::sin(phi)};
  Eigen::Vector2d n(-f.direction.y(), f.direction.x());
  double rho = n.dot(c);
  if (rho < 0) {
    n = -n;
    rho = -rho;
  }
  f.line.rho = rho;
  f.line.beta = wrap_angle(std::atan2(n.y(), n.x()));
  double ss = 0;
  for (const auto& p : points) {
    const double r = n.dot(p) - rho;
    ss += r * r;
  }
  f.rms = std::sqrt(ss / static_cast<double>(points.size()));
  f.first = c + f.direction * f.direction.dot(points.front() - c);
  f.last = c + f.direction * f.direction.dot(points.back() - c);
  return f;
}

}  // namespace locbench::laser
