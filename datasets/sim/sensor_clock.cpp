#include "datasets/sim/sensor_clock.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace locbench::sim {

SensorClock::SensorClock(const SensorTiming& timing, double step, Rng rng)
    : enabled_(timing.enabled), rate_(timing.rate), jitter_(timing.jitter), step_(step), rng_(rng) {
  next_ = enabled_ ? std::max<std::int64_t>(0, instant(0)) : std::numeric_limits<std::int64_t>::max();
}

std::int64_t SensorClock::instant(std::int64_t k) {
  if (rate_ <= 0.0) return k;
  double t = static_cast<double>(k) / rate_;
  if (jitter_ > 0.0) {
    const double limit = 0.45 / rate_;
    t += std::clamp(rng_.normal(0.0, jitter_), -limit, limit);
  }
  return std::llround(t / step_);
}

void SensorClock::advance() {
  if (!enabled_) return;
  ++k_;
  next_ = std::max(next_ + 1, instant(k_));
}

}  // namespace locbench::sim
