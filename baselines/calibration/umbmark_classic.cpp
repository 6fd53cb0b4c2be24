#include "baselines/calibration/umbmark_classic.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/units.h"

namespace locbench::baselines::calibration {

namespace {

struct Angles {
  double beta = 0.0;
  double alpha = 0.0;
};

// 2.3a/2.3b and 2.6a/2.6b. The thesis multiplies by 180°/π to get degrees; we stay in radians.
Angles type_a_b(const UmbmarkCentroids& c, double side, UmbmarkAngleFormula f) {
  const double k = -4.0 * side;
  const Angles x{(c.cw.x() - c.ccw.x()) / k, (c.cw.x() + c.ccw.x()) / k};
  const Angles y{(c.cw.y() + c.ccw.y()) / k, (c.cw.y() - c.ccw.y()) / k};
  switch (f) {
    case UmbmarkAngleFormula::kX: return x;
    case UmbmarkAngleFormula::kY: return y;
    case UmbmarkAngleFormula::kMean: return {0.5 * (x.beta + y.beta), 0.5 * (x.alpha + y.alpha)};
  }
  return x;
}

}  // namespace

ClassicUmbmarkResult classic_umbmark(const UmbmarkInput& in, const ClassicUmbmarkOptions& options) {
  check_umbmark_input(in, false);
  ClassicUmbmarkResult r;
  r.centroids = umbmark_centroids(in.runs);
  const auto [beta, alpha] = type_a_b(r.centroids, in.side_length, options.angles);
  r.beta = beta;
  r.alpha = alpha;

  // 2.4: R = (L/2)/sin(β/2). Written through the curvature 1/R so that β = 0 gives E_d = 1.
  const double curvature = 2.0 * std::sin(beta / 2.0) / in.side_length;
  r.radius = curvature != 0.0 ? 1.0 / curvature : std::numeric_limits<double>::infinity();
  const double b = in.nominal.wheelbase;  // 2.5 uses the nominal B (the actual one is unknown)
  if (std::abs(beta) >= kPi / 2.0 || std::abs(curvature) * b / 2.0 >= 1.0) {
    throw std::invalid_argument("classic UMBmark: β = " + std::to_string(to_deg(beta)) +
                                "° per leg is beyond what eq. 2.4–2.5 describe (|β| < 90°, "
                                "|R| > B/2); check the units of the return errors");
  }
  // 2.5: E_d = (R + B/2)/(R − B/2) = (1 + B/(2R))/(1 − B/(2R)).
  r.E_d = (1.0 + curvature * b / 2.0) / (1.0 - curvature * b / 2.0);

  // 2.7–2.8: E_b = 90°/(90° − α).
  if (std::abs(alpha) >= kPi / 2.0) {
    throw std::invalid_argument("classic UMBmark: |α| = " + std::to_string(to_deg(alpha)) +
                                "° ≥ 90°; check the units of the return errors");
  }
  r.E_b = (kPi / 2.0) / (kPi / 2.0 - alpha);
  r.B_actual = r.E_b * in.nominal.wheelbase;

  // 2.15, 2.9–2.13.
  r.E_s = in.tape_measure_scale;
  r.D_a = r.E_s * in.nominal.mean_diameter();
  r.c_L = 2.0 / (r.E_d + 1.0);
  r.c_R = 2.0 / (1.0 / r.E_d + 1.0);
  r.D_L = r.c_L * r.D_a;
  r.D_R = r.c_R * r.D_a;
  r.corrected = {r.c_L * r.E_s * in.nominal.diameter_left, r.c_R * r.E_s * in.nominal.diameter_right, r.B_actual};
  return r;
}

}  // namespace locbench::baselines::calibration
