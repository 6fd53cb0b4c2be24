#pragma once
// One factory per experiment file; registry.cpp lists them in order.
#include <memory>

#include "benchmarks/experiments/experiment.h"

namespace locbench::experiments {

std::unique_ptr<Experiment> make_odometry_sim_corridor();
std::unique_ptr<Experiment> make_odometry_real_logs();

}  // namespace locbench::experiments
