#include "algorithms/slip/slip_detector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/enum_names.h"
#include "core/errors.h"
#include "core/option_fields.h"
#include "core/statistics.h"

namespace locbench::slip {

SlipModel fit_slip_model(std::span<const double> d) {
  if (d.size() < 2) throw std::invalid_argument("fit_slip_model: need at least 2 samples");
  double s = 0.0, s2 = 0.0;
  for (double v : d) {
    s += v;
    s2 += v * v;
  }
  const double n = static_cast<double>(d.size());
  SlipModel m;
  m.mean = s / n;
  m.stddev = std::sqrt(std::max(0.0, s2 / n - m.mean * m.mean));
  if (!(m.stddev > 0.0)) throw std::invalid_argument("fit_slip_model: zero spread");
  return m;
}

// SlipDetectorOptions's fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, SlipDetectorOptions& o) {
  v.field("probability", o.probability, "", open(0.0, 1.0), "P{|Δθ' − μ|/σ ≤ z} under no slip (§3.2.3)");
  v.flag("check_disturbance", o.check_disturbance, "apply the compass-disturbance rule (rule 3)");
  v.field("disturbance_margin", o.disturbance_margin, "rad", non_negative(), "widens the rule-3 interval on each side");
}

void validate(const SlipDetectorOptions& o) { validate_fields(o, "SlipDetectorOptions"); }

LOCBENCH_OPTIONS_JSON(SlipDetectorOptions)

double slip_threshold(double probability) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw UsageError("slip_threshold: probability must be in (0, 1)");
  }
  return normal_quantile(0.5 * (1.0 + probability));
}

constexpr EnumNames<SampleStatus, 4> kSampleStatuses{{{SampleStatus::kNoSlip, "no_slip"},
                                                      {SampleStatus::kLeftSlip, "left_slip"},
                                                      {SampleStatus::kRightSlip, "right_slip"},
                                                      {SampleStatus::kCompassDisturbed, "compass_disturbed"}}};

const char* to_string(SampleStatus s) { return enum_name(kSampleStatuses, s); }

bool compass_disturbed(const WheelDisplacement& u, double theta_c, double wheelbase, double margin) {
  const double a = -u.left / wheelbase, b = u.right / wheelbase;
  return theta_c > std::max(a, b) + margin || theta_c < std::min(a, b) - margin;
}

SlipWheel slipped_wheel(double theta_c, double theta_e) {
  if (theta_c > theta_e) return SlipWheel::kLeft;
  if (theta_c < theta_e) return SlipWheel::kRight;
  return SlipWheel::kNone;
}

BodyIncrement corrected_increment(const WheelDisplacement& u, double theta_c, double wheelbase, SlipWheel wheel) {
  switch (wheel) {
    case SlipWheel::kLeft:  // (3.14–3.15): the left wheel really moved U_R − B tan θ_C
      return {0.5 * (2.0 * u.right - wheelbase * std::tan(theta_c)), theta_c};
    case SlipWheel::kRight:  // (3.16–3.17): the right wheel really moved U_L + B tan θ_C
      return {0.5 * (2.0 * u.left + wheelbase * std::tan(theta_c)), theta_c};
    case SlipWheel::kNone: break;
  }
  return body_increment(u, wheelbase);  // (3.12–3.13)
}

WheelDisplacement wheels_for(const BodyIncrement& b, double wheelbase) {
  return {b.distance - 0.5 * wheelbase * b.rotation, b.distance + 0.5 * wheelbase * b.rotation};
}

SlipDetector::SlipDetector(const SlipModel& model, const SlipDetectorOptions& options, double wheelbase)
    : model_(model), options_(options), wheelbase_(wheelbase) {
  validate(options_);
  if (!(model_.stddev > 0.0) || !std::isfinite(model_.mean)) {
    throw UsageError("SlipDetector: the slip model needs a finite mean and σ > 0");
  }
  require_positive_wheelbase(wheelbase_, "SlipDetector");
  z_ = slip_threshold(options_.probability);
}

SlipDecision SlipDetector::classify(const WheelDisplacement& u, double theta_c) const {
  SlipDecision d;
  d.theta_c = theta_c;
  d.theta_e = (u.right - u.left) / wheelbase_;  // (3.1)
  d.delta_prime = d.theta_e - theta_c;          // (3.2)
  d.z_score = (d.delta_prime - model_.mean) / model_.stddev;
  d.increment = body_increment(u, wheelbase_);
  d.wheels = u;
  if (options_.check_disturbance && compass_disturbed(u, theta_c, wheelbase_, options_.disturbance_margin)) {
    d.status = SampleStatus::kCompassDisturbed;  // rule 3: the compass cannot correct
    return d;
  }
  if (std::abs(d.z_score) <= z_) return d;                // rule 5
  const SlipWheel w = slipped_wheel(theta_c, d.theta_e);  // rule 4, §3.3
  if (w == SlipWheel::kNone) return d;
  d.status = w == SlipWheel::kLeft ? SampleStatus::kLeftSlip : SampleStatus::kRightSlip;
  d.increment = corrected_increment(u, theta_c, wheelbase_, w);
  d.wheels = wheels_for(d.increment, wheelbase_);
  return d;
}

}  // namespace locbench::slip
