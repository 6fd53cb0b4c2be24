// The list of experiments. To add one: write benchmarks/experiments/<name>.cpp with a factory,
// declare it in experiments_list.h, and append it here (see README, "Adding an experiment").
#include "benchmarks/experiments/framework/experiment.h"
#include "benchmarks/experiments/framework/experiments_list.h"

namespace locbench::experiments {

const std::vector<std::unique_ptr<Experiment>>& all_experiments() {
  static const std::vector<std::unique_ptr<Experiment>> list = [] {
    std::vector<std::unique_ptr<Experiment>> v;
    v.push_back(make_odometry_sim_corridor());
    v.push_back(make_odometry_real_logs());
    v.push_back(make_calibration_umbmark_trilobot());
    v.push_back(make_calibration_umbmark_borenstein());
    v.push_back(make_calibration_identifiability());
    v.push_back(make_calibration_real_logs());
    v.push_back(make_slip_normality_table_3_1());
    v.push_back(make_slip_compass_ekf_table_3_2());
    v.push_back(make_slip_indirect_kf_tables_3_3_3_4());
    v.push_back(make_slip_ikf_vs_calibration());
    v.push_back(make_laser_matcher_accuracy());
    v.push_back(make_laser_table_6_1());
    v.push_back(make_laser_table_6_2());
    v.push_back(make_laser_tables_6_3_6_4());
    v.push_back(make_laser_tracking_table_6_5());
    v.push_back(make_laser_real_logs());
    v.push_back(make_laser_rwht_bins());
    v.push_back(make_noise_tables());
    v.push_back(make_noise_resolution_sweep());
    v.push_back(make_noise_quantization_sigma());
    v.push_back(make_noise_real_logs());
    v.push_back(make_diagnosis_false_alarms());
    v.push_back(make_diagnosis_power());
    v.push_back(make_diagnosis_real_logs());
    v.push_back(make_diagnosis_sim_to_real());
    v.push_back(make_global_topological_example());
    v.push_back(make_global_sim());
    v.push_back(make_global_real_logs());
    return v;
  }();
  return list;
}

}  // namespace locbench::experiments
