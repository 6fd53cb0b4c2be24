// The list of experiments. To add one: write benchmarks/experiments/<name>.cpp with a factory,
// declare it in experiments_list.h, and append it here (see README, "Adding an experiment").
#include "benchmarks/experiments/experiment.h"
#include "benchmarks/experiments/experiments_list.h"

namespace locbench::experiments {

const std::vector<std::unique_ptr<Experiment>>& all_experiments() {
  static const std::vector<std::unique_ptr<Experiment>> list = [] {
    std::vector<std::unique_ptr<Experiment>> v;
    v.push_back(make_odometry_sim_corridor());
    v.push_back(make_odometry_real_logs());
    return v;
  }();
  return list;
}

}  // namespace locbench::experiments
