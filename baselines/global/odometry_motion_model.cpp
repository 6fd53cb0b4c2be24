#include "baselines/global/odometry_motion_model.h"

#include <cmath>

#include "baselines/global/options_fields.h"
#include "core/angle.h"
#include "core/errors.h"

namespace locbench::baselines::global {

void validate(const OdometryMotionOptions& o) { validate_fields(o, "OdometryMotionOptions"); }

OdometryDelta odometry_delta(const Pose2& from, const Pose2& to) {
  const double dx = to.x - from.x, dy = to.y - from.y;
  OdometryDelta d;
  d.trans = std::hypot(dx, dy);
  if (d.trans < 1e-9) {
    d.trans = 0.0;
    d.rot1 = 0.0;
  } else {
    d.rot1 = angle_diff(std::atan2(dy, dx), from.theta);
    if (std::abs(d.rot1) > kPi / 2.0) {  // driving backwards
      d.rot1 = wrap_angle(d.rot1 + kPi);
      d.trans = -d.trans;
    }
  }
  d.rot2 = angle_diff(angle_diff(to.theta, from.theta), d.rot1);
  return d;
}

bool moved_less_than(const OdometryDelta& d, const Pose2& from, const Pose2& to, double min_distance,
                     double min_angle) {
  return std::abs(d.trans) < min_distance && std::abs(angle_diff(to.theta, from.theta)) < min_angle;
}

Pose2 apply_delta(const Pose2& p, const OdometryDelta& d) {
  const double h = p.theta + d.rot1;
  return {p.x + d.trans * std::cos(h), p.y + d.trans * std::sin(h), h + d.rot2};
}

OdometryDelta delta_sigma(const OdometryDelta& d, const OdometryMotionOptions& o) {
  const double r1 = d.rot1 * d.rot1, t = d.trans * d.trans, r2 = d.rot2 * d.rot2;
  OdometryDelta s;
  s.rot1 = std::sqrt(o.alpha1 * r1 + o.alpha2 * t + o.min_rotation_sigma * o.min_rotation_sigma / 2.0);
  s.trans = std::sqrt(o.alpha3 * t + o.alpha4 * (r1 + r2) + o.min_translation_sigma * o.min_translation_sigma);
  s.rot2 = std::sqrt(o.alpha1 * r2 + o.alpha2 * t + o.min_rotation_sigma * o.min_rotation_sigma / 2.0);
  return s;
}

Pose2 sample_motion(const Pose2& p, const OdometryDelta& d, const OdometryMotionOptions& o, Rng& rng) {
  const OdometryDelta s = delta_sigma(d, o);
  OdometryDelta n;
  n.rot1 = d.rot1 + rng.normal(0.0, s.rot1);
  n.trans = d.trans + rng.normal(0.0, s.trans);
  n.rot2 = d.rot2 + rng.normal(0.0, s.rot2);
  return apply_delta(p, n);
}

}  // namespace locbench::baselines::global
