#include "baselines/laser/angular_index.h"

#include <algorithm>
#include <cmath>

namespace locbench::baselines::laser {

AngularIndex::AngularIndex(const std::vector<Eigen::Vector2d>& points)
    : order_(points.size()), angle_(points.size()), point_(points.size()), unit_(points.size()) {
  std::vector<double> a(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    order_[i] = i;
    a[i] = std::atan2(points[i].y(), points[i].x());
  }
  std::sort(order_.begin(), order_.end(), [&](std::size_t x, std::size_t y) { return a[x] < a[y]; });
  for (std::size_t k = 0; k < order_.size(); ++k) {
    angle_[k] = a[order_[k]];
    point_[k] = points[order_[k]];
    const double norm = point_[k].norm();
    unit_[k] = norm > 0.0 ? Eigen::Vector2d(point_[k] / norm) : Eigen::Vector2d::Zero();
  }
}

bool AngularIndex::nearest(const Eigen::Vector2d& q, double max_d2, std::size_t& index, double& d2) const {
  const std::size_t m = order_.size();
  if (m == 0) return false;
  const double r = q.norm(), aq = std::atan2(q.y(), q.x());
  const auto start = static_cast<std::size_t>(std::lower_bound(angle_.begin(), angle_.end(), aq) - angle_.begin());
  double best = max_d2;
  bool found = false;
  const auto visit = [&](std::size_t k) {
    const double d = (point_[k] - q).squaredNorm();
    if (d < best || (!found && d <= best)) {
      best = d;
      index = order_[k];
      found = true;
    }
  };
  // The squared lower bound of the distance to the k-th point by angle: r·sin Δa, the distance
  // from q to the ray through the point, is |q × u| for the ray's direction u (r when Δa ≥ π/2,
  // q·u ≤ 0); rounding never prunes a nearer point.
  const auto bound2 = [&](std::size_t k) {
    const Eigen::Vector2d& u = unit_[k];
    const double b = q.dot(u) <= 0.0 ? r : std::abs(q.x() * u.y() - q.y() * u.x());
    return b * b * (1.0 - 1e-12);
  };
  std::size_t up = start % m, down = (start + m - 1) % m, seen = 0;
  bool up_open = true, down_open = true;
  while ((up_open || down_open) && seen < m) {
    if (up_open) {
      if (bound2(up) > best) {
        up_open = false;
      } else {
        visit(up);
        up = (up + 1) % m;
        if (++seen >= m) break;
      }
    }
    if (down_open) {
      if (bound2(down) > best) {
        down_open = false;
      } else {
        visit(down);
        down = (down + m - 1) % m;
        ++seen;
      }
    }
  }
  d2 = best;
  return found;
}

}  // namespace locbench::baselines::laser
