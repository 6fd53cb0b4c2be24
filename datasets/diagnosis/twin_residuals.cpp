#include "datasets/diagnosis/twin_residuals.h"

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/motion_windows.h"
#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::sim {

WindowResiduals nominal_residuals(const Log& log, double window_s, double time_shift, std::size_t min_windows) {
  diagnosis::WindowOptions o;
  o.duration = window_s;
  o.max_gap = std::max(o.max_gap, 0.5 * window_s);
  o.min_windows = min_windows;
  const diagnosis::MotionData d = diagnosis::build_motion_data(log, o);
  const diagnosis::OdometryModel nominal;
  WindowResiduals out;
  out.reference = d.reference == diagnosis::ReferenceKind::kRelations ? "relations" : "truepos";
  for (const auto& w : d.windows) {
    const auto r = diagnosis::window_residual(d, w, nominal);
    if (!r.valid || r.heading_only) continue;
    out.t0.push_back(w.t0 + time_shift);
    out.t1.push_back(w.t1 + time_shift);
    out.r.push_back({r.r[0], r.r[1], r.r[2]});
  }
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> pair_windows(const WindowResiduals& a, const WindowResiduals& b,
                                                              double tolerance) {
  std::vector<std::size_t> order(b.t0.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return b.t0[p] < b.t0[q]; });
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < a.t0.size(); ++i) {
    auto it = std::lower_bound(order.begin(), order.end(), a.t0[i] - tolerance,
                               [&](std::size_t k, double v) { return b.t0[k] < v; });
    for (; it != order.end() && b.t0[*it] <= a.t0[i] + tolerance; ++it) {
      if (std::abs(b.t1[*it] - a.t1[i]) <= tolerance) {
        out.emplace_back(i, *it);
        break;
      }
    }
  }
  return out;
}

std::vector<double> component(const WindowResiduals& w, int c,
                              const std::vector<std::pair<std::size_t, std::size_t>>& pairs, bool first) {
  std::vector<double> out;
  out.reserve(pairs.size());
  for (const auto& [i, j] : pairs) out.push_back(w.r[first ? i : j][static_cast<std::size_t>(c)]);
  return out;
}

}  // namespace locbench::sim
