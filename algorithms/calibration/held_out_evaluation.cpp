#include "algorithms/calibration/held_out_evaluation.h"

#include <cmath>
#include <stdexcept>

namespace locbench::calibration {

PoseErrors relative_motion_errors(const CalibrationData& data, const ModelParameters& p) {
  // One trajectory holding each sample's predicted motion over [2i, 2i + 1] (its start pose
  // repeated at 2i + 2 for the next), and one relation per sample over the same times.
  std::vector<StampedPose> poses;
  std::vector<Relation> relations;
  Pose2 at;
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const double t = 2.0 * static_cast<double>(i);
    const Pose2 end = at * predict_reference(data, data.samples[i], p);
    poses.push_back({t, at});
    poses.push_back({t + 1.0, end});
    relations.push_back({t, t + 1.0, data.samples[i].reference});
    at = end;
  }
  PoseErrors e = relation_error(Trajectory(std::move(poses)), relations);
  // Report the samples' own times where they have them.
  for (std::size_t i = 0; i < e.t.size() && i < data.samples.size(); ++i) {
    if (std::isfinite(data.samples[i].t_start)) e.t[i] = data.samples[i].t_start;
  }
  return e;
}

HeldOutEvaluation evaluate_held_out(const CalibrationData& data, const MlCalibrationOptions& options,
                                    double training_fraction) {
  const std::size_t n = data.samples.size();
  const auto split = static_cast<std::size_t>(std::floor(training_fraction * static_cast<double>(n)));
  if (!(training_fraction > 0.0 && training_fraction < 1.0) || split == 0 || split >= n) {
    throw std::invalid_argument("evaluate_held_out: need samples on both sides of the split");
  }
  return evaluate_held_out(subset(data, 0, split), subset(data, split, n), options);
}

HeldOutEvaluation evaluate_held_out(const CalibrationData& train, const CalibrationData& test,
                                    const MlCalibrationOptions& options) {
  if (train.samples.empty() || test.samples.empty() || train.kind != test.kind) {
    throw std::invalid_argument("evaluate_held_out: need samples of one kind in both sets");
  }
  HeldOutEvaluation out;
  out.calibration = calibrate_ml(train, options);
  out.training_samples = train.samples.size();
  out.evaluation_samples = test.samples.size();
  ModelParameters nominal = nominal_parameters(test);
  nominal.sensor = out.calibration.estimate.sensor;
  const PoseErrors before = relative_motion_errors(test, nominal);
  const PoseErrors after = relative_motion_errors(test, out.calibration.estimate);
  out.nominal_translation = error_statistics(before.translation);
  out.nominal_rotation = error_statistics(before.rotation);
  out.calibrated_translation = error_statistics(after.translation);
  out.calibrated_rotation = error_statistics(after.rotation);
  auto reduction = [](double after_rmse, double before_rmse) {
    return before_rmse > 0.0 ? 1.0 - after_rmse / before_rmse : 0.0;
  };
  out.translation_rmse_reduction = reduction(out.calibrated_translation.rmse, out.nominal_translation.rmse);
  out.rotation_rmse_reduction = reduction(out.calibrated_rotation.rmse, out.nominal_rotation.rmse);
  return out;
}

}  // namespace locbench::calibration
