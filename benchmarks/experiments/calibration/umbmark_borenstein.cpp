// Experiment calibration/umbmark_borenstein: UMBmark, classic and improved, on a LabMate-like robot on Borenstein &
// Feng's 4 m square. The experiment is harness/calibration_umbmark.h, shared with the other robot.
#include "experiment_framework/registry.h"
#include "pipelines/calibration_umbmark.h"

namespace locbench::experiments::calibration_umbmark_borenstein {

const Registration<CalibrationUmbmark> calibration_umbmark_borenstein_registration("umbmark_borenstein");

}  // namespace locbench::experiments::calibration_umbmark_borenstein
