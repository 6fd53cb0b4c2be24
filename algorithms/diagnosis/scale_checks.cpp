#include "algorithms/diagnosis/scale_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

ScaleChecks scale_checks(const MotionData& d, double time_offset) {
  ScaleChecks c;
  OdometryModel m;
  m.time_offset = time_offset;
  std::vector<double> ratios;
  double ref_len = 0.0, odo_len = 0.0, ro = 0.0, oo = 0.0, tt = 0.0, to = 0.0;
  for (const auto& w : d.windows) {
    const auto ref = reference_window(d, w, m);
    if (!ref) continue;
    const Pose2 odo = predict_window(d, w, OdometryModel{});
    const double r = std::hypot(ref->x, ref->y), o = std::hypot(odo.x, odo.y);
    if (o > 0.02) ratios.push_back(r / o);
    ref_len += r;
    odo_len += o;
    ro += r * o;
    oo += o * o;
    to += ref->theta * odo.theta;
    tt += odo.theta * odo.theta;
    ++c.windows;
  }
  c.path_length_ratio = odo_len > 0.0 ? ref_len / odo_len : 0.0;
  c.ls_velocity_scale = oo > 0.0 ? ro / oo : 0.0;
  c.ls_turn_scale = tt > 0.0 ? to / tt : 0.0;
  if (!ratios.empty()) {
    const auto mid = ratios.begin() + static_cast<long>(ratios.size() / 2);
    std::nth_element(ratios.begin(), mid, ratios.end());
    c.median_window_ratio = *mid;
  }
  return c;
}

std::string scale_disagreement(const std::string& log, double value, double lo, double hi, const ScaleChecks& c,
                               double tolerance, const std::string& what) {
  const double a = std::min(c.path_length_ratio, c.ls_velocity_scale) - tolerance;
  const double b = std::max(c.path_length_ratio, c.ls_velocity_scale) + tolerance;
  if (hi >= a && lo <= b) return "";
  std::string s = fmt::format(
      "{}: the kept {} {:.3f} [{:.3f}, {:.3f}] lies outside the independent checks' "
      "range ±{:.2f} ([{:.3f}, {:.3f}])",
      log, what, value, lo, hi, tolerance, a, b);
  if (what == "velocity scale" && std::abs(c.median_window_ratio - c.path_length_ratio) > tolerance) {
    s += fmt::format(
        ": the per-window ratio is skewed (median {:.3f}, path-length ratio {:.3f}); the diagnosis's "
        "Student-t fit follows the typical window, the sums follow the mean, which the windows that "
        "lose distance pull down (drive_stall models such windows when the held-out data support it)",
        c.median_window_ratio, c.path_length_ratio);
  }
  return s;
}

}  // namespace locbench::diagnosis
