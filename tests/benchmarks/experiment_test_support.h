#pragma once
// What several experiment tests ask of an experiment's results.
#include <stdexcept>
#include <string>

#include "experiment_framework/experiment.h"
#include "reports/report_json.h"

namespace locbench::experiments::test_support {

// The result named `name` (method/dataset/variant); std::runtime_error if there is none.
inline const reports::MetricResult& find_result(const reports::ExperimentResults& r, const std::string& name) {
  for (const auto& m : r.results) {
    if (m.name() == name) return m;
  }
  throw std::runtime_error("no result " + name);
}

// The experiment on its defaults with no dataset folder (/nonexistent): what it says when its
// real data are absent.
inline reports::ExperimentResults run_without_data(const Experiment& e) {
  RunOptions o;
  o.data_root = "/nonexistent";
  return e.run(e.default_config(), o);
}

// The experiment's results as JSON (2 Monte-Carlo runs on its defaults) on `threads` worker
// threads: equal for any thread count.
inline nlohmann::json results_on_threads(const Experiment& e, int threads) {
  RunOptions o;
  o.runs = 2;
  o.threads = threads;
  return reports::results_to_json(e.run(e.default_config(), o));
}

}  // namespace locbench::experiments::test_support
