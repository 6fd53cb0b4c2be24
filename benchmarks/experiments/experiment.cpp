#include "benchmarks/experiments/experiment.h"

#include "algorithms/core/errors.h"

namespace locbench::experiments {

const Experiment* find_experiment(const std::string& name) {
  for (const auto& e : all_experiments()) {
    if (e->name() == name) return e.get();
  }
  return nullptr;
}

int monte_carlo_runs(const Experiment& e, const nlohmann::json& config, const RunOptions& options) {
  const int runs = options.runs.value_or(config.at("runs").get<int>());
  if (runs < 1) throw UsageError(e.name() + ": runs must be ≥ 1");
  return runs;
}

nlohmann::json merge_config(const nlohmann::json& defaults, const nlohmann::json& overrides,
                            const std::string& path) {
  if (!overrides.is_object()) throw UsageError("configuration" + path + ": expected an object");
  nlohmann::json out = defaults;
  for (const auto& [key, value] : overrides.items()) {
    const std::string where = path + "." + key;
    if (!defaults.contains(key)) throw UsageError("configuration: unknown option " + where.substr(1));
    const nlohmann::json& d = defaults.at(key);
    if (d.is_object() && value.is_object() && !d.empty()) {
      out[key] = merge_config(d, value, where);
    } else if (d.is_number() && value.is_number()) {
      out[key] = value;
    } else if (d.type() != value.type() && !d.is_null()) {
      throw UsageError("configuration: option " + where.substr(1) + " expects a " +
                       std::string(d.type_name()) + ", got a " + value.type_name());
    } else {
      out[key] = value;
    }
  }
  return out;
}

}  // namespace locbench::experiments
