#include "algorithms/filters/compass_odometry_input.h"

#include <cmath>
#include <stdexcept>

namespace locbench::filters {

std::vector<CompassOdometrySample> pair_encoder_compass(std::span<const EncoderReading> encoders,
                                                        std::span<const CompassReading> compass,
                                                        const NominalModel& model, double max_offset) {
  if (!(max_offset >= 0.0)) throw std::invalid_argument("pair_encoder_compass: max_offset < 0");
  std::vector<CompassOdometrySample> out;
  if (encoders.size() < 2) return out;
  out.reserve(encoders.size() - 1);
  std::size_t c = 0;  // first compass reading not yet used
  for (std::size_t k = 1; k < encoders.size(); ++k) {
    CompassOdometrySample s;
    s.t = encoders[k].t;
    s.encoder_index = k;
    s.u = displacement_from_ticks(model, encoders[k].left - encoders[k - 1].left,
                                  encoders[k].right - encoders[k - 1].right);
    // Skip readings too old for this sample, then take the nearest of the remaining ones.
    while (c < compass.size() && compass[c].t < s.t - max_offset) ++c;
    std::size_t best = compass.size();
    for (std::size_t i = c; i < compass.size() && compass[i].t <= s.t + max_offset; ++i) {
      if (best == compass.size() || std::abs(compass[i].t - s.t) < std::abs(compass[best].t - s.t)) {
        best = i;
      }
    }
    if (best < compass.size()) {
      s.compass = compass[best].heading;
      c = best + 1;
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace locbench::filters
