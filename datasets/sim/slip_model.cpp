#include "datasets/sim/slip_model.h"

#include <cmath>

namespace locbench::sim {

double SlipModel::probability(MotionPhase phase, double wheel_speed, double duration) const {
  if (phase == MotionPhase::kIdle) return 0.0;
  const SlipProfile& p = phase == MotionPhase::kStraight ? config_.straight : config_.turn;
  if (config_.unit == SlipRateUnit::kPerSample) return p.rate;
  return 1.0 - std::exp(-p.rate * wheel_speed * duration);
}

std::optional<ActiveSlip> SlipModel::start_interval(MotionPhase phase, double wheel_speed, double duration) {
  const double p = probability(phase, wheel_speed, duration);
  if (p <= 0.0 || !rng_.bernoulli(p)) return std::nullopt;
  const SlipProfile& prof = phase == MotionPhase::kStraight ? config_.straight : config_.turn;
  ActiveSlip s;
  s.wheel = rng_.bernoulli(0.5) ? Side::kLeft : Side::kRight;
  s.fraction = rng_.uniform(prof.magnitude_min, prof.magnitude_max);
  return s;
}

}  // namespace locbench::sim
