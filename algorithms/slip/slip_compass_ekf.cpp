#include "algorithms/slip/slip_compass_ekf.h"

#include <cmath>

#include "algorithms/filters/compass_ekf.h"
#include "core/angle.h"
#include "core/errors.h"

namespace locbench::slip {
using locbench::filters::CompassEkf;

SlipEkfRun run_slip_ekf(std::span<const SlipSample> samples, std::optional<double> initial_compass,
                        const SlipModel& compass_model, const std::optional<SlipModel>& gyro_model,
                        const SlipEkfOptions& options, double wheelbase, const Pose2& start) {
  if (options.gyro_fallback && !gyro_model) {
    throw UsageError("run_slip_ekf: gyro_fallback needs the gyro's slip model");
  }
  if (!(options.latch_tolerance > 0.0)) throw UsageError("run_slip_ekf: latch_tolerance must be > 0");
  const SlipDetector compass_detector(compass_model, options.detector, wheelbase);
  std::optional<SlipDetector> gyro_detector;
  if (options.gyro_fallback) {
    SlipDetectorOptions g = options.detector;
    g.check_disturbance = false;  // the gyro is not magnetically disturbed
    gyro_detector.emplace(*gyro_model, g, wheelbase);
  }
  const Matrix3 q = options.process_noise.asDiagonal();
  CompassEkf ekf([q](const Vector3&, const WheelDisplacement&, double) { return q; }, options.compass_variance,
                 options.initial_covariance.asDiagonal(), wheelbase, start);
  SlipEkfRun run;
  run.steps.reserve(samples.size());
  std::optional<double> previous_compass = initial_compass;
  double offset = 0.0;  // latched unexplained compass jump [rad]
  for (const SlipSample& s : samples) {
    SlipEkfStep step;
    const double theta_prev = ekf.mean()(2);
    const double theta_e = (s.u.right - s.u.left) / wheelbase;  // (3.1)
    std::optional<double> theta_c;
    if (s.compass && previous_compass) theta_c = angle_diff(*s.compass, *previous_compass);
    if (s.compass) previous_compass = s.compass;

    WheelDisplacement u = s.u;
    std::optional<double> z;  // the heading measurement
    if (!options.correct_slip) {
      step.decision.increment = body_increment(u, wheelbase);
      step.decision.wheels = u;
      step.decision.theta_e = theta_e;
      z = wrap_angle(theta_prev + theta_e);  // first EKF: Z = θ̂(k−1) + θ_E(k)
      step.source = HeadingSource::kPseudoEncoder;
    } else {
      bool disturbed = false;
      if (theta_c) {
        step.decision = compass_detector.classify(u, *theta_c);
        disturbed = step.decision.status == SampleStatus::kCompassDisturbed;
        if (options.latch_disturbance) {
          if (disturbed) offset += *theta_c - theta_e;
          disturbed = disturbed || std::abs(offset) > options.latch_tolerance;
        }
      } else {
        disturbed = !s.compass;  // no reading at all: nothing to correct with
      }
      step.compass_disturbed = disturbed && s.compass.has_value();
      if (!disturbed && theta_c) {
        step.had_increment = true;
        z = *s.compass;
        step.source = HeadingSource::kCompass;
      } else if (!disturbed && s.compass) {
        z = *s.compass;  // first sample: absolute reading but no increment yet
        step.source = HeadingSource::kCompass;
        step.decision = SlipDecision{};
        step.decision.theta_e = theta_e;
        step.decision.increment = body_increment(u, wheelbase);
        step.decision.wheels = u;
      } else if (options.gyro_fallback && s.gyro_increment) {
        step.had_increment = true;
        step.decision = gyro_detector->classify(u, *s.gyro_increment);
        z = wrap_angle(theta_prev + *s.gyro_increment);
        step.source = HeadingSource::kPseudoGyro;
      } else {
        step.decision = SlipDecision{};
        step.decision.status = s.compass ? SampleStatus::kCompassDisturbed : SampleStatus::kNoSlip;
        step.decision.theta_e = theta_e;
        step.decision.increment = body_increment(u, wheelbase);
        step.decision.wheels = u;
        z = wrap_angle(theta_prev + theta_e);  // §3.6 rule 1
        step.source = HeadingSource::kPseudoEncoder;
      }
      u = step.decision.wheels;
    }
    if (step.decision.slipped()) ++run.slips_detected;
    if (step.compass_disturbed) ++run.disturbed_samples;
    step.mean = ekf.step(u, z).mean;
    run.steps.push_back(step);
  }
  run.final_pose = to_pose(ekf.mean());
  return run;
}

}  // namespace locbench::slip
