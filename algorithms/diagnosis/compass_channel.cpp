#include "algorithms/diagnosis/compass_channel.h"

#include <algorithm>
#include <cmath>

#include "algorithms/core/angle.h"
#include "algorithms/core/statistics.h"
#include "algorithms/core/units.h"
#include "algorithms/diagnosis/motion_windows.h"

namespace locbench::diagnosis {

std::vector<CompassResidual> compass_residuals(const CompassData& d, double time_offset) {
  std::vector<CompassResidual> out(d.readings.size());
  for (std::size_t i = 0; i < d.readings.size(); ++i) {
    const double t = d.readings[i].t - time_offset;
    const auto p = interpolate_truth(d.truth, t);
    const auto a = interpolate_truth(d.truth, t - 0.05), b = interpolate_truth(d.truth, t + 0.05);
    if (!p) continue;
    out[i].t = d.readings[i].t;
    out[i].r = angle_diff(d.readings[i].heading, p->theta);
    out[i].x = p->x;
    out[i].y = p->y;
    out[i].turn_rate = a && b ? angle_diff(b->theta, a->theta) / 0.1 : 0.0;
    out[i].valid = true;
  }
  return out;
}

namespace {

double log_density(double e, double step, double sigma) {
  if (step <= 0.0) return -0.5 * (e * e / (sigma * sigma)) - std::log(sigma * std::sqrt(2.0 * kPi));
  const double hi = (e + 0.5 * step) / sigma, lo = (e - 0.5 * step) / sigma;
  // Φ(hi) − Φ(lo) through the upper tails for accuracy far from 0.
  const double mass = lo > 0.0 ? normal_upper_tail(lo) - normal_upper_tail(hi)
                               : normal_upper_tail(-hi) - normal_upper_tail(-lo);
  return std::log(std::max(mass, 1e-300) / step);
}

bool in_zone(const CompassZone& z, double x, double y) {
  return z.enabled && std::hypot(x - z.x, y - z.y) <= z.radius;
}

}  // namespace

double compass_nll(const CompassData& d, const CompassModel& m, const std::vector<std::size_t>& index) {
  const auto res = compass_residuals(d, m.time_offset);
  double nll = 0.0;
  const std::size_t n = index.empty() ? res.size() : index.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto& c = res[index.empty() ? k : index[k]];
    if (!c.valid) {
      nll -= log_density(0.0, m.step, m.sigma);
      continue;
    }
    const double e = wrap_angle(c.r - m.bias - (in_zone(m.zone, c.x, c.y) ? m.zone.bias : 0.0));
    nll -= log_density(e, m.step, m.sigma);
  }
  return nll;
}

CompassZone best_compass_zone(const CompassData& d, const CompassModel& m,
                              const std::vector<std::size_t>& index) {
  const auto res = compass_residuals(d, m.time_offset);
  std::vector<const CompassResidual*> use;
  for (std::size_t k : index) {
    if (res[k].valid) use.push_back(&res[k]);
  }
  CompassZone best;
  double best_gain = 0.0;
  std::size_t searched = 0;
  const double var = m.sigma * m.sigma + m.step * m.step / 12.0;
  const std::size_t stride = std::max<std::size_t>(1, use.size() / 150);
  for (std::size_t c = 0; c < use.size(); c += stride) {
    for (double radius : {0.25, 0.5, 1.0, 2.0, 4.0}) {
      double sum = 0.0;
      std::size_t inside = 0;
      for (const auto* u : use) {
        if (std::hypot(u->x - use[c]->x, u->y - use[c]->y) <= radius) {
          sum += wrap_angle(u->r - m.bias);
          ++inside;
        }
      }
      if (inside < 10 || use.size() - inside < 10) continue;
      ++searched;
      const double gain = sum * sum / (2.0 * var * static_cast<double>(inside));  // Gaussian ΔNLL
      if (gain > best_gain) {
        best_gain = gain;
        best = {true, use[c]->x, use[c]->y, radius, sum / static_cast<double>(inside), 0};
      }
    }
  }
  best.candidates = searched;
  return best;
}

}  // namespace locbench::diagnosis
