#include "algorithms/diagnosis/scale_checks.h"

#include <cmath>

#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

ScaleChecks scale_checks(const MotionData& d, double time_offset) {
  ScaleChecks c;
  OdometryModel m;
  m.time_offset = time_offset;
  double ref_len = 0.0, odo_len = 0.0, ro = 0.0, oo = 0.0, tt = 0.0, to = 0.0;
  for (const auto& w : d.windows) {
    const auto ref = reference_window(d, w, m);
    if (!ref) continue;
    const Pose2 odo = predict_window(d, w, OdometryModel{});
    const double r = std::hypot(ref->x, ref->y), o = std::hypot(odo.x, odo.y);
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
  return c;
}

}  // namespace locbench::diagnosis
