#include "pipelines/twin/twin_residuals.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::sim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::array<double, 3>> residuals(const diagnosis::MotionData& d) {
  const diagnosis::OdometryModel nominal;
  std::vector<std::array<double, 3>> out;
  out.reserve(d.windows.size());
  for (const auto& w : d.windows) {
    const auto r = diagnosis::window_residual(d, w, nominal);
    if (!r.valid || r.heading_only) {
      out.push_back({kNaN, kNaN, kNaN});
    } else {
      out.push_back({r.r[0], r.r[1], r.r[2]});
    }
  }
  return out;
}

}  // namespace

diagnosis::MotionData residual_windows(const Log& log, double window_s, std::size_t min_windows) {
  diagnosis::WindowOptions o;
  o.duration = window_s;
  o.max_gap = std::max(o.max_gap, 0.5 * window_s);
  o.min_windows = min_windows;
  return diagnosis::build_motion_data(log, o);
}

std::vector<std::array<double, 3>> nominal_residuals(const diagnosis::MotionData& d) { return residuals(d); }

std::vector<std::array<double, 3>> twin_residuals(const diagnosis::MotionData& d, const Log& twin, double time_origin) {
  diagnosis::MotionData t = d;
  std::vector<TruePose> truth = twin.truth;
  for (auto& p : truth) p.t += time_origin;
  if (t.reference == diagnosis::ReferenceKind::kRelations) {
    for (auto& w : t.windows) {
      const auto a = diagnosis::interpolate_truth(truth, w.t0), b = diagnosis::interpolate_truth(truth, w.t1);
      w.reference = a && b ? between(*a, *b) : Pose2(kNaN, kNaN, 0.0);
    }
    auto out = residuals(t);
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (!std::isfinite(t.windows[k].reference.x)) out[k] = {kNaN, kNaN, kNaN};
    }
    return out;
  }
  t.reference = diagnosis::ReferenceKind::kTruePose;
  t.truth = std::move(truth);
  return residuals(t);
}

std::vector<std::vector<double>> common_component(const std::vector<const std::vector<std::array<double, 3>>*>& sets,
                                                  int c) {
  std::vector<std::vector<double>> out(sets.size());
  if (sets.empty()) return out;
  const std::size_t n = sets.front()->size();
  for (std::size_t k = 0; k < n; ++k) {
    bool finite = true;
    for (const auto* s : sets) finite = finite && k < s->size() && std::isfinite((*s)[k][static_cast<std::size_t>(c)]);
    if (!finite) continue;
    for (std::size_t i = 0; i < sets.size(); ++i) out[i].push_back((*sets[i])[k][static_cast<std::size_t>(c)]);
  }
  return out;
}

}  // namespace locbench::sim
