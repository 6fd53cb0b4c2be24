#include "algorithms/diagnosis/odometry_battery.h"

#include <cmath>

#include "algorithms/diagnosis/residual_tests.h"

namespace locbench::diagnosis {

OdoResiduals odometry_residuals(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index) {
  OdoResiduals o;
  auto rate = [](const MotionWindow& v) { return v.t1 > v.t0 ? v.turn / (v.t1 - v.t0) : 0.0; };
  for (std::size_t k : index) {
    const auto& w = d.windows[k];
    const auto r = window_residual(d, w, m);
    if (!r.valid) continue;
    o.along.push_back(r.r[0] / std::sqrt(r.variance[0]));
    o.lateral.push_back(r.r[1] / std::sqrt(r.variance[1]));
    o.heading.push_back(r.r[2] / std::sqrt(r.variance[2]));
    o.distance.push_back(w.signed_distance);
    o.turn.push_back(w.turn);
    o.speed.push_back(w.t1 > w.t0 ? w.distance / (w.t1 - w.t0) : 0.0);
    o.travel.push_back(w.wheel_travel);
    o.cos_h.push_back(std::cos(w.heading));
    o.sin_h.push_back(std::sin(w.heading));
    o.x.push_back(w.x);
    o.y.push_back(w.y);
    const auto& prev = d.windows[k > 0 ? k - 1 : k];
    const auto& next = d.windows[k + 1 < d.windows.size() ? k + 1 : k];
    o.dturn.push_back(0.5 * (rate(next) - rate(prev)));
  }
  return o;
}

std::vector<ResidualTest> odometry_battery(const MotionData& d, const OdoResiduals& o) {
  std::vector<ResidualTest> t;
  const bool pos = d.reference != ReferenceKind::kCompass;
  t.push_back(bias_test(o.heading, "heading"));
  if (pos) t.push_back(bias_test(o.along, "along_track"));
  t.push_back(dependence_test(o.heading, o.distance, "drift_with_distance", "heading", "distance"));
  if (pos) t.push_back(dependence_test(o.along, o.distance, "drift_with_distance", "along_track", "distance"));
  // A reference frame turned against the direction of travel moves the robot sideways in
  // proportion to the distance driven.
  if (pos) t.push_back(dependence_test(o.lateral, o.distance, "drift_with_distance", "lateral", "distance"));
  t.push_back(dependence_test(o.heading, o.turn, "drift_with_turning", "heading", "turn"));
  if (pos) t.push_back(dependence_test(o.along, o.speed, "speed_dependence", "along_track", "speed"));
  t.push_back(dependence_test(o.heading, o.speed, "speed_dependence", "heading", "speed"));
  t.push_back(dependence_test(o.heading, o.cos_h, "heading_dependence", "heading", "cos(heading)"));
  t.push_back(dependence_test(o.heading, o.sin_h, "heading_dependence", "heading", "sin(heading)"));
  if (d.reference == ReferenceKind::kTruePose) {
    t.push_back(dependence_test(o.heading, o.x, "position_dependence", "heading", "x"));
    t.push_back(dependence_test(o.heading, o.y, "position_dependence", "heading", "y"));
  }
  t.push_back(skewness_test(o.heading, "heading"));
  t.push_back(heavy_tail_test(o.heading, "heading"));
  if (pos) t.push_back(heavy_tail_test(o.along, "along_track"));
  t.push_back(heteroscedasticity_test(o.heading, o.travel, "heading", "wheel_travel"));
  if (pos) t.push_back(heteroscedasticity_test(o.along, o.travel, "along_track", "wheel_travel"));
  t.push_back(autocorrelation_test(o.heading, "heading"));
  if (d.reference != ReferenceKind::kRelations) {
    t.push_back(dependence_test(o.heading, o.dturn, "lead_lag", "heading", "turn-rate change"));
  }
  return t;
}

}  // namespace locbench::diagnosis
