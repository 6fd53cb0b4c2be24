// Experiment calibration/umbmark_trilobot: UMBmark, classic and improved, on the thesis's Trilobot (1.6 m square,
// Table 2.1 beside our figures). The experiment is harness/calibration_umbmark.h, shared with the other robot.
#include "experiment_framework/registry.h"
#include "pipelines/calibration_umbmark.h"

namespace locbench::experiments::calibration_umbmark_trilobot {

const Registration<CalibrationUmbmark> calibration_umbmark_trilobot_registration("umbmark_trilobot");

}  // namespace locbench::experiments::calibration_umbmark_trilobot
