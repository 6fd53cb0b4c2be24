#include "pipelines/filter_models.h"

#include "algorithms/diagnosis/diagnosis.h"
#include "core/errors.h"
#include "core/json_file.h"

namespace locbench::experiments::landmarks {
namespace {

// The filter's sensor model of the diagnosis's landmark model (the same quantities, named for
// the filter).
LandmarkSensorModel sensor_of(const diagnosis::LandmarkModel& m) {
  LandmarkSensorModel s;
  s.range_scale = m.range_scale;
  s.range_bias = m.range_bias;
  s.range_off_axis_linear = m.range_off_axis_linear;
  s.range_off_axis = m.range_off_axis;
  s.field_of_view = m.field_of_view;
  s.bearing_bias = m.bearing_bias;
  s.range_sigma = m.sigma_range;
  s.bearing_sigma = m.sigma_bearing;
  s.range_noise_slope = m.range_noise_slope;
  s.bearing_noise_turn_slope = m.bearing_noise_turn_slope;
  s.time_offset = m.time_offset;
  s.dof = m.dof;
  if (m.position_error_id >= 0) s.landmark_shift[m.position_error_id] = {m.position_error_dx, m.position_error_dy};
  return s;
}

FilterModels from_fitted(const diagnosis::FittedModels& f, const LandmarkSensorModel& sensor,
                         const std::vector<std::string>& causes, const std::string& source) {
  if (!f.odometry) throw InputError(source, 0, "models: no odometry model to run a filter with");
  if (f.odometry_kind == "encoder") {
    throw InputError(source, 0, "models: an encoder-count odometry model; landmark localization runs on velocity logs");
  }
  FilterModels m;
  m.noise_window_s = f.odometry_window_s;
  m.diagnosed_motion = *f.odometry;
  m.nominal_sensor = sensor;
  m.diagnosed_sensor = f.landmark ? sensor_of(*f.landmark) : sensor;
  m.causes = causes;
  m.source = source;
  return m;
}

}  // namespace

FilterModels filter_models(const diagnosis::Diagnosis& d, const LandmarkSensorModel& sensor) {
  diagnosis::FittedModels f;
  f.odometry = d.odometry_model;
  f.odometry_kind = d.odometry_kind;
  f.odometry_window_s = d.noise_window_s;
  f.landmark = d.landmark_model;
  FilterModels m = from_fitted(f, sensor, d.detected, "diagnosis of " + d.log);
  m.nominal_motion.sigma_x = d.noise_sigma_x;  // the nominal model: no cause, its own fitted floor
  m.nominal_motion.sigma_y = d.noise_sigma_y;
  m.nominal_motion.sigma_theta = d.noise_sigma_theta;
  return m;
}

FilterModels read_filter_models(const std::filesystem::path& file, const LandmarkSensorModel& sensor) {
  const nlohmann::json report = read_json_file(file);
  diagnosis::FittedModels f;
  try {
    f = diagnosis::read_fitted_models(report);
  } catch (const UsageError& e) {
    throw InputError(file.string(), 0, e.what());
  }
  std::vector<std::string> causes;
  if (report.contains("detected") && report["detected"].is_array()) {
    for (const auto& c : report["detected"])
      if (c.is_string()) causes.push_back(c.get<std::string>());
  }
  FilterModels m = from_fitted(f, sensor, causes, file.string());
  // The nominal model's floor from the same report (its "noise_floor", when present).
  if (report.contains("noise_floor") && report["noise_floor"].is_object()) {
    const auto& n = report["noise_floor"];
    m.nominal_motion.sigma_x = n.value("sigma_x_m", 0.0);
    m.nominal_motion.sigma_y = n.value("sigma_y_m", 0.0);
    m.nominal_motion.sigma_theta = n.value("sigma_theta_rad", 0.0);
  } else {
    m.nominal_motion.sigma_x = m.diagnosed_motion.sigma_x;
    m.nominal_motion.sigma_y = m.diagnosed_motion.sigma_y;
    m.nominal_motion.sigma_theta = m.diagnosed_motion.sigma_theta;
  }
  return m;
}

}  // namespace locbench::experiments::landmarks
