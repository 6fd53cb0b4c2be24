#pragma once
// A log's odometry cut into short windows, each paired with what the reference says the robot
// really did over the same time: the residual data every odometry test and cause is fitted on.
//
// Odometry is either encoder counts (ENCODER: ΔN_L, ΔN_R per sample, mapped to wheel travel by
// the PARAM model) or a dead-reckoned pose (ODOM: each step's ΔD, Δθ from consecutive poses).
// The reference is TRUEPOS ground truth (interpolated at the odometry times, so a time offset
// between the two can be fitted), Freiburg .relations (one window per relation) or, with
// neither, the compass (heading increments only).
#include <optional>
#include <string>
#include <vector>

#include "core/angle.h"
#include "core/log.h"
#include "core/pose2.h"
#include "core/robot_params.h"
#include "core/sensor_data.h"

namespace locbench::diagnosis {

enum class OdometryKind { kEncoder, kPose };
enum class ReferenceKind { kTruePose, kRelations, kCompass };

std::string to_string(OdometryKind k);
std::string to_string(ReferenceKind k);

// One odometry sample interval (logged times).
struct OdometryStep {
  double t0 = 0.0, t1 = 0.0;
  double a = 0.0;  // encoder: ΔN_L [ticks]; pose: ΔD [m] (signed, along the mid heading)
  double b = 0.0;  // encoder: ΔN_R [ticks]; pose: Δθ [rad]
};

// A pose step's length and logged rates a/Δt and b/Δt (0 over a step of no length).
struct StepRates {
  double dt = 0.0, v = 0.0, rate = 0.0;
};
inline StepRates step_rates(const OdometryStep& s) {
  const double dt = s.t1 - s.t0;
  return {dt, dt > 0.0 ? s.a / dt : 0.0, dt > 0.0 ? s.b / dt : 0.0};
}

struct MotionWindow {
  std::size_t first = 0, last = 0;  // steps [first, last)
  double t0 = 0.0, t1 = 0.0;        // logged times of the window's ends
  Pose2 reference;                  // relations: the reference motion (fixed)
  // Covariates under the nominal model.
  double distance = 0.0;  // |ΔD| summed [m]
  double signed_distance = 0.0;
  double turn = 0.0;          // Σ Δθ [rad]
  double wheel_travel = 0.0;  // Σ (|U_L| + |U_R|) [m] (pose odometry: |ΔD|·2 + |Δθ|·B)
  double heading = 0.0;       // reference heading at t0 [rad] (0 for relations)
  double x = 0.0, y = 0.0;    // reference position at t0 [m]
};

struct WindowOptions {
  double duration = 1.0;         // target window length [s]
  double max_gap = 1.0;          // a longer gap between odometry samples ends a window [s]
  double min_step = 0.08;        // consecutive samples are merged into sub-steps this long [s]
  std::size_t min_windows = 40;  // fewer is "too short a log"
};

struct MotionData {
  OdometryKind odometry = OdometryKind::kEncoder;
  ReferenceKind reference = ReferenceKind::kTruePose;
  NominalModel nominal;  // encoder logs; pose logs use wheelbase only for covariates (0 if unknown)
  std::vector<OdometryStep> steps;
  std::vector<MotionWindow> windows;
  std::vector<TruePose> truth;          // kTruePose
  std::vector<CompassReading> compass;  // every COMPASS reading (the reference when kCompass)
  double compass_step = 0.0;            // PARAM compass_resolution [rad]; 0 when not declared
  double reference_interval = 0.0;      // median sampling interval of truth or compass [s]
  std::string describe() const;         // e.g. "TRUEPOS ground truth (4812 poses)"
};

// Throws InputError (naming the log) when the log has no usable odometry, no reference, too few
// windows, a PARAM compass_resolution that is not a number of radians, or a nominal model that is
// missing or not in SI units (a wheelbase above 5 m, metres
// per tick above 0.01 m — millimetres by mistake).
MotionData build_motion_data(const Log& log, const WindowOptions& options = {});

// The window's covariates under the nominal model (distance, signed distance, turn, wheel
// travel) from its steps in `m`, set afresh (a twin that changes the steps refreshes them).
void fill_covariates(const MotionData& m, MotionWindow& w);

// How many times build_motion_data has been called in this process (for tests).
std::size_t build_motion_data_calls();

// The reference pose at logged time t (linear interpolation, heading on the circle); nullopt
// outside the truth's time span.
std::optional<Pose2> interpolate_truth(const std::vector<TruePose>& truth, double t);
// interpolate_truth for many times in (roughly) increasing order: the same values, bit for bit,
// with the bracketing record found by stepping from the previous one instead of a search
// (the compass likelihood interpolates three times per reading at every evaluation).
class TruthInterpolator {
 public:
  explicit TruthInterpolator(const std::vector<TruePose>& truth) : truth_(truth) {}
  std::optional<Pose2> at(double t);

 private:
  const std::vector<TruePose>& truth_;
  std::size_t next_ = 0;  // index of the first record with time ≥ the last query's
};

// The true pose at a reading's time and the turn rate around it.
struct TruthSample {
  Pose2 pose;
  double turn_rate = 0.0;  // heading change over t ± 0.05 s [rad/s]; 0 where the truth lacks either end
};

// Calls f(i, sample) for each reading i, in order, whose time less `time_offset` the truth covers.
template <class Readings, class F>
void for_each_truth_sample(const std::vector<TruePose>& truth, const Readings& readings, double time_offset, F&& f) {
  TruthInterpolator interpolator(truth);
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const double t = readings[i].t - time_offset;
    const auto a = interpolator.at(t - 0.05), p = interpolator.at(t), b = interpolator.at(t + 0.05);
    if (p) f(i, TruthSample{*p, a && b ? angle_diff(b->theta, a->theta) / 0.1 : 0.0});
  }
}

// The compass heading at time t (interpolated along the shorter arc); nullopt outside.
std::optional<double> interpolate_compass(const std::vector<CompassReading>& compass, double t);

}  // namespace locbench::diagnosis
