#pragma once
// The odometry action model (Thrun, Burgard & Fox, Probabilistic Robotics §5.4): the relative
// motion between two odometry poses is split into a first rotation δrot1, a translation δtrans
// and a second rotation δrot2; each is perturbed by zero-mean noise with
//   σ²(rot1)  = α1 δrot1² + α2 δtrans²
//   σ²(trans) = α3 δtrans² + α4 (δrot1² + δrot2²)
//   σ²(rot2)  = α1 δrot2² + α2 δtrans²
// plus a small floor so a standing robot's belief still diffuses a little.
#include <nlohmann/json.hpp>

#include "core/pose2.h"
#include "core/rng.h"

namespace locbench::baselines::global {

struct OdometryMotionOptions {
  double alpha1 = 0.05;                 // rotation noise from rotation [rad²/rad²]
  double alpha2 = 0.01;                 // rotation noise from translation [rad²/m²]
  double alpha3 = 0.05;                 // translation noise from translation [m²/m²]
  double alpha4 = 0.005;                // translation noise from rotation [m²/rad²]
  double min_translation_sigma = 0.01;  // [m] per update
  double min_rotation_sigma = 0.005;    // [rad] per update
};
void to_json(nlohmann::json& j, const OdometryMotionOptions& o);
void from_json(const nlohmann::json& j, OdometryMotionOptions& o);  // strict; UsageError
void validate(const OdometryMotionOptions& o);

struct OdometryDelta {
  double rot1 = 0.0;
  double trans = 0.0;
  double rot2 = 0.0;
};
// δ from odometry pose `from` to `to` (both in the odometry frame). A backwards move is a
// negative translation (no ±π first rotation).
OdometryDelta odometry_delta(const Pose2& from, const Pose2& to);
// Whether the odometry moved from `from` to `to` (δ = odometry_delta(from, to)) by less than
// `min_distance` [m] and turned by less than `min_angle` [rad]: the filters skip such updates.
bool moved_less_than(const OdometryDelta& d, const Pose2& from, const Pose2& to, double min_distance, double min_angle);
// The pose reached from p by δ.
Pose2 apply_delta(const Pose2& p, const OdometryDelta& d);
// Standard deviations of (rot1, trans, rot2) for δ.
OdometryDelta delta_sigma(const OdometryDelta& d, const OdometryMotionOptions& o);
// One sample of the motion model from p.
Pose2 sample_motion(const Pose2& p, const OdometryDelta& d, const OdometryMotionOptions& o, Rng& rng);

}  // namespace locbench::baselines::global
