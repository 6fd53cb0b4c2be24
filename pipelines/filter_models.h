#pragma once
// The motion and landmark-sensor models a filter runs with, taken from a diagnosis: its nominal
// model (no cause, the fitted white floor) and its diagnosed model (the nominal model plus every
// detected cause), for the odometry and, when the log has landmarks, the landmark channel.
// Either fitted in the same run (the first half of a log) or read from a model file — a report
// `locbench diagnose --report` wrote on another log of the same robot.
#include <filesystem>
#include <string>
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "algorithms/diagnosis/odometry_model.h"
#include "pipelines/landmark_tracking.h"

namespace locbench::experiments::landmarks {

struct FilterModels {
  diagnosis::OdometryModel nominal_motion, diagnosed_motion;
  LandmarkSensorModel nominal_sensor, diagnosed_sensor;
  double noise_window_s = 1.0;  // the floor's σ are per window of this length
  // The time correlation of the diagnosed motion model's window residuals (on the data the models
  // were fitted on; none: white).
  MotionNoiseStructure diagnosed_motion_structure;
  std::vector<std::string> causes;  // the detected causes in the diagnosed model
  std::string source;               // where they come from
};

// The models of a diagnosis. `sensor` is the nominal landmark sensor (used as is when the
// diagnosis has no landmark channel).
FilterModels filter_models(const diagnosis::Diagnosis& d, const LandmarkSensorModel& sensor);

// The models of a diagnosis report file (`locbench diagnose --report`, schema
// locbench.diagnosis/1). Throws InputError naming the file for a missing or malformed file or a
// report without models.
FilterModels read_filter_models(const std::filesystem::path& file, const LandmarkSensorModel& sensor);

}  // namespace locbench::experiments::landmarks
