// The registry behind Registration (registry.h) and all_experiments() (experiment.h).
#include "experiment_framework/registry.h"

#include <algorithm>
#include <stdexcept>

namespace locbench::experiments {
namespace {

// A function-local static: registrars in other files may run before any global here is built.
std::vector<ExperimentFactory>& factories() {
  static std::vector<ExperimentFactory> list;
  return list;
}

}  // namespace

void register_experiment(ExperimentFactory make) { factories().push_back(std::move(make)); }

std::vector<std::unique_ptr<Experiment>> make_sorted(const std::vector<ExperimentFactory>& makers) {
  std::vector<std::unique_ptr<Experiment>> v;
  for (const ExperimentFactory& make : makers) v.push_back(make());
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a->name() < b->name(); });
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i]->name() == v[i - 1]->name()) {
      throw std::logic_error("two experiments are registered as \"" + v[i]->name() + "\"");
    }
  }
  return v;
}

const std::vector<std::unique_ptr<Experiment>>& all_experiments() {
  static const std::vector<std::unique_ptr<Experiment>> list = make_sorted(factories());
  return list;
}

}  // namespace locbench::experiments
