#pragma once
// Classic UMBmark calibration (Borenstein & Feng; thesis eq. 2.3–2.13 with 2.15): from the
// centroids of the clockwise and counter-clockwise return errors, the Type B angle β gives the
// radius of the curved legs and E_d = D_R/D_L, the Type A angle α gives E_b = B_actual/B_nominal,
// and the tape-measured scale E_s fixes the mean diameter D_a = E_s·D_n. SI units: m, rad.
// An independent implementation: it uses the core measurement types only.
#include "core/robot_params.h"
#include "core/umbmark_measurements.h"

namespace locbench::baselines::calibration {

struct ClassicUmbmarkOptions {
  UmbmarkAngleFormula angles = UmbmarkAngleFormula::kX;  // 2.3a/2.6a by default
};

struct ClassicUmbmarkResult {
  UmbmarkCentroids centroids;  // of the input runs, with E_max,syst
  double beta = 0.0;           // Type B angle per leg [rad] (2.3), > 0 when D_R > D_L
  double alpha = 0.0;          // Type A angle per 90° turn [rad] (2.6), > 0 when turns fall short
  double radius = 0.0;         // R of the curved leg [m] (2.4); ±∞ when β = 0; sign of β
  double E_d = 1.0;            // (2.5), D_R/D_L relative to the nominal wheels
  double E_b = 1.0;            // (2.8)
  double E_s = 1.0;            // the tape-measured scale used (2.15)
  double B_actual = 0.0;       // (2.7) [m]
  double D_a = 0.0;            // E_s·D_n (2.15) [m]
  double D_L = 0.0;            // (2.10) [m]
  double D_R = 0.0;            // (2.11) [m]
  double c_L = 1.0;            // correction factor of the left wheel (2.12), dimensionless
  double c_R = 1.0;            // (2.13)
  // The nominal geometry to drive with after calibration: {D_L, D_R, B_actual}. With unequal
  // nominal wheels D_L = c_L·E_s·D_n,L and D_R = c_R·E_s·D_n,R (equal nominal wheels: 2.10–2.11).
  WheelGeometry corrected;
};

// Throws std::invalid_argument for input check_umbmark_input rejects, or when the angles are
// too large for 2.5/2.8 (|R| ≤ B/2 or α ≥ 90°).
ClassicUmbmarkResult classic_umbmark(const UmbmarkInput& in, const ClassicUmbmarkOptions& options = {});

}  // namespace locbench::baselines::calibration
