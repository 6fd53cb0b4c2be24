#pragma once
// Held-out evaluation of the ML calibration: calibrate on the first part of a data set's samples
// and compare the calibrated with the uncalibrated (nominal) odometry on the rest, by the
// relative-motion error of each held-out sample — Kümmerle et al.'s relation error
// (trajectory_error.h: Δ_ref⁻¹ Δ_est per relation), with the sample intervals as relations.
#include <cstddef>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/ml_calibration.h"
#include "core/trajectory_error.h"

namespace locbench::calibration {

// Per-sample relative-motion errors (translation [m], |rotation| [rad]) of the model's
// predicted reference against each sample's reference, computed with relation_error.
PoseErrors relative_motion_errors(const CalibrationData& data, const ModelParameters& p);

struct HeldOutEvaluation {
  MlCalibrationResult calibration;  // on the training samples
  std::size_t training_samples = 0;
  std::size_t evaluation_samples = 0;
  // Relation errors on the held-out samples: nominal parameters vs calibrated ones.
  ErrorStatistics nominal_translation, nominal_rotation;
  ErrorStatistics calibrated_translation, calibrated_rotation;
  // 1 − calibrated RMSE / nominal RMSE (positive = the calibration helps).
  double translation_rmse_reduction = 0.0;
  double rotation_rmse_reduction = 0.0;
};

// Calibrates on samples [0, ⌊fraction·n⌋) and evaluates on the rest (in the data's order — time
// order for log-derived data). With a sensor reference, the nominal odometry is compared with
// the sensor pose held at the calibrated one, so the numbers measure the odometry alone.
// Throws std::invalid_argument unless 0 < fraction < 1 leaves samples on both sides.
HeldOutEvaluation evaluate_held_out(const CalibrationData& data, const MlCalibrationOptions& options = {},
                                    double training_fraction = 0.5);

// The same with the two sets given: calibrate on `training`, evaluate on `evaluation` (e.g. the
// held-out half restricted to short relations). Both must have samples and the same kind.
HeldOutEvaluation evaluate_held_out(const CalibrationData& training, const CalibrationData& evaluation,
                                    const MlCalibrationOptions& options = {});

}  // namespace locbench::calibration
