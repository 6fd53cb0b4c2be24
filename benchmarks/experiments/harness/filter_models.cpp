#include "benchmarks/experiments/harness/filter_models.h"

#include "algorithms/diagnosis/cause_catalog.h"
#include "core/errors.h"
#include "core/json_file.h"

namespace locbench::experiments::landmarks {

FilterModels filter_models(const diagnosis::Diagnosis& d, const LandmarkSensorModel& sensor) {
  FilterModels m;
  m.noise_window_s = d.noise_window_s;
  m.nominal_motion.sigma_x = d.noise_sigma_x;
  m.nominal_motion.sigma_y = d.noise_sigma_y;
  m.nominal_motion.sigma_theta = d.noise_sigma_theta;
  m.diagnosed_motion = m.nominal_motion;
  m.nominal_sensor = sensor;
  m.diagnosed_sensor = sensor;
  for (const diagnosis::Cause& c : d.causes) {
    if (!c.detected || c.channel != "odometry") continue;
    const diagnosis::CauseSpec& spec = diagnosis::cause_spec(c.id);
    for (const diagnosis::Estimate& e : c.parameters) {
      for (const diagnosis::CauseParameter& p : spec.params) {
        if (p.name == e.name && p.field) m.diagnosed_motion.*(p.field) = e.value;
      }
    }
    m.causes.push_back(c.id);
  }
  m.source = "diagnosis of " + d.log;
  return m;
}

FilterModels read_filter_models(const std::filesystem::path& file, const LandmarkSensorModel& sensor) {
  (void)sensor;
  throw InputError(file.string(), 0, "model files are not read yet");
}

}  // namespace locbench::experiments::landmarks
