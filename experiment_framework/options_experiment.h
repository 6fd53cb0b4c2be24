#pragma once
// An experiment that runs once (not Monte-Carlo) with an options struct (experiment_options.h):
// default_config() is the options' JSON and run() reads the merged configuration back with the
// strict reader before handing it to run_with.
#include <nlohmann/json.hpp>

#include "experiment_framework/experiment.h"
#include "experiment_framework/experiment_options.h"

namespace locbench::experiments {

template <typename Options>
class OptionsExperiment : public Experiment {
 public:
  using Experiment::Experiment;
  nlohmann::json default_config() const final { return options_json(Options{}); }
  reports::ExperimentResults run(const nlohmann::json& config, const RunOptions& run) const final {
    return run_with(read_options<Options>(config, name()), run);
  }
  virtual reports::ExperimentResults run_with(const Options& options, const RunOptions& run) const = 0;
};

}  // namespace locbench::experiments
