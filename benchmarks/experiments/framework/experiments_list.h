#pragma once
// One factory per experiment file; registry.cpp lists them in order.
#include <memory>

#include "benchmarks/experiments/framework/experiment.h"

namespace locbench::experiments {

std::unique_ptr<Experiment> make_odometry_sim_corridor();
std::unique_ptr<Experiment> make_odometry_real_logs();
std::unique_ptr<Experiment> make_calibration_umbmark_trilobot();
std::unique_ptr<Experiment> make_calibration_umbmark_borenstein();
std::unique_ptr<Experiment> make_calibration_identifiability();
std::unique_ptr<Experiment> make_calibration_real_logs();
std::unique_ptr<Experiment> make_slip_normality_table_3_1();
std::unique_ptr<Experiment> make_slip_compass_ekf_table_3_2();
std::unique_ptr<Experiment> make_slip_indirect_kf_tables_3_3_3_4();
std::unique_ptr<Experiment> make_slip_ikf_vs_calibration();
std::unique_ptr<Experiment> make_laser_matcher_accuracy();
std::unique_ptr<Experiment> make_laser_table_6_1();
std::unique_ptr<Experiment> make_laser_table_6_2();
std::unique_ptr<Experiment> make_laser_tables_6_3_6_4();
std::unique_ptr<Experiment> make_laser_tracking_table_6_5();
std::unique_ptr<Experiment> make_laser_real_logs();
std::unique_ptr<Experiment> make_laser_rwht_bins();
std::unique_ptr<Experiment> make_noise_tables();
std::unique_ptr<Experiment> make_noise_resolution_sweep();
std::unique_ptr<Experiment> make_noise_quantization_sigma();
std::unique_ptr<Experiment> make_noise_real_logs();
std::unique_ptr<Experiment> make_diagnosis_false_alarms();
std::unique_ptr<Experiment> make_diagnosis_power();
std::unique_ptr<Experiment> make_diagnosis_real_logs();
std::unique_ptr<Experiment> make_diagnosis_sim_to_real();
std::unique_ptr<Experiment> make_global_topological_example();
std::unique_ptr<Experiment> make_global_sim();
std::unique_ptr<Experiment> make_global_real_logs();

}  // namespace locbench::experiments
