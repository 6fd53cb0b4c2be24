#pragma once
// One true wheel and its encoder. The wheel's rim position q is kept in (true) encoder ticks;
// the encoder reports the integer count floor(q), i.e. floor(true cumulative rim travel / true
// metres per tick). The sub-tick remainder e = q − floor(q) carries over between samples, so the
// travel measured in one sample is U = C·N with U_act = U + e_k − e_{k+1} (eq. 4.12–4.13); when
// the remainders are independent and uniform on [0, C] the residual is triangular on [−C, C]
// with variance C²/6 (eq. 4.14–4.21).
// The ground travel (what moves the robot) is the rim travel minus slip plus floor noise.
#include <cmath>
#include <cstdint>

namespace locbench::sim {

struct Wheel {
  double meters_per_tick = 1.0;  // true C [m/tick]
  double q = 0.0;                // rim position [true ticks]
  double ground = 0.0;           // cumulative ground travel [m]
  double slip = 0.0;             // cumulative travel lost to slip [m]

  std::int64_t count() const { return static_cast<std::int64_t>(std::floor(q)); }
  double rim() const { return q * meters_per_tick; }  // cumulative rim travel [m]
};

// The residual of one sample: true rim travel minus the travel the counts say, under the true
// metres per tick (e_k − e_{k+1} of eq. 4.13, in metres).
inline double quantization_residual(double rim_travel, std::int64_t count_increment, double meters_per_tick) {
  return rim_travel - static_cast<double>(count_increment) * meters_per_tick;
}

}  // namespace locbench::sim
