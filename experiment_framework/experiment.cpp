#include "experiment_framework/experiment.h"

#include "core/errors.h"
#include "reports/report_json.h"
#include "reports/shard_report.h"

namespace locbench::experiments {

const Experiment* find_experiment(const std::string& name) {
  for (const auto& e : all_experiments()) {
    if (e->name() == name) return e.get();
  }
  return nullptr;
}

reports::ExperimentResults Experiment::start_results(const nlohmann::json& configuration) const {
  reports::ExperimentResults out;
  out.experiment = name();
  out.description = description();
  out.configuration = configuration;
  out.notes = info_.reading;
  return out;
}

int Experiment::task_count(const nlohmann::json&, const RunOptions&) const { return 1; }

std::vector<nlohmann::json> Experiment::run_tasks(const nlohmann::json& config, const RunOptions& options,
                                                  const std::vector<int>& tasks) const {
  std::vector<nlohmann::json> records;
  for (int t : tasks) {
    if (t != 0) throw std::logic_error(name() + ": task " + std::to_string(t) + " of 1");
    records.push_back(reports::canonical_record(reports::results_to_json(run(config, options))));
  }
  return records;
}

reports::ExperimentResults Experiment::summarise_records(const nlohmann::json&, const RunOptions&,
                                                         const std::vector<nlohmann::json>& records) const {
  if (records.size() != 1) throw std::logic_error(name() + ": expected the record of its one task");
  return reports::results_from_json(records.front(), name() + " (shard record)");
}

nlohmann::json merge_config(const nlohmann::json& defaults, const nlohmann::json& overrides, const std::string& path) {
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
      throw UsageError("configuration: option " + where.substr(1) + " expects a " + std::string(d.type_name()) +
                       ", got a " + value.type_name());
    } else {
      out[key] = value;
    }
  }
  return out;
}

}  // namespace locbench::experiments
