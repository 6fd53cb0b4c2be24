#pragma once
// The odometry channel's residual tests: each window's residual under a model, standardized by
// the model's variance, set beside the window's distance, turn, speed, travel, heading and
// position, and the battery of tests (residual_tests.h) run on them: bias, drifts, speed and
// heading dependence, shape, heteroscedasticity, autocorrelation, lead/lag.
#include <cstddef>
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

struct OdoResiduals {
  std::vector<double> along, lateral, heading, distance, turn, speed, travel, cos_h, sin_h, x, y, dturn;
};

// The windows `index` that the (shifted) reference covers.
OdoResiduals odometry_residuals(const MotionData& d, const OdometryModel& m, const std::vector<std::size_t>& index);
std::vector<ResidualTest> odometry_battery(const MotionData& d, const OdoResiduals& o);

}  // namespace locbench::diagnosis
