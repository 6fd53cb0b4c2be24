#include "baselines/laser/angular_index.h"

#include <algorithm>
#include <cmath>

#include "core/angle.h"

namespace locbench::baselines::laser {

AngularIndex::AngularIndex(const std::vector<Eigen::Vector2d>& points)
    : points_(points), order_(points.size()), angle_(points.size()) {
  std::vector<double> a(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    order_[i] = i;
    a[i] = std::atan2(points[i].y(), points[i].x());
  }
  std::sort(order_.begin(), order_.end(), [&](std::size_t x, std::size_t y) { return a[x] < a[y]; });
  for (std::size_t k = 0; k < order_.size(); ++k) angle_[k] = a[order_[k]];
}

bool AngularIndex::nearest(const Eigen::Vector2d& q, double max_d2, std::size_t& index, double& d2) const {
  const std::size_t m = order_.size();
  if (m == 0) return false;
  const double r = q.norm(), aq = std::atan2(q.y(), q.x());
  const auto start = static_cast<std::size_t>(std::lower_bound(angle_.begin(), angle_.end(), aq) - angle_.begin());
  double best = max_d2;
  bool found = false;
  const auto visit = [&](std::size_t k) {
    const double d = (points_[order_[k]] - q).squaredNorm();
    if (d < best || (!found && d <= best)) {
      best = d;
      index = order_[k];
      found = true;
    }
  };
  // The squared lower bound of the distance to the k-th point by angle; the rounding of sin and
  // atan2 never prunes a nearer point.
  const auto bound2 = [&](std::size_t k) {
    const double da = std::abs(wrap_angle(angle_[k] - aq));
    const double b = da >= 0.5 * kPi ? r : r * std::sin(da);
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
