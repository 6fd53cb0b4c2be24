#pragma once
// An experiment names its inputs, the methods it compares and the metrics; it runs them (over
// seeds where it is Monte-Carlo) and returns results. It does not print or write files.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reports/report.h"

namespace locbench::experiments {

struct RunOptions {
  std::uint64_t seed = 1;
  std::optional<int> runs;               // Monte-Carlo runs; the experiment's default if unset
  std::filesystem::path data_root;       // real datasets (LOCBENCH_DATA)
  std::function<void(double)> progress;  // fraction done in [0, 1]; may be empty
  int threads = 1;                       // worker threads (results never depend on it)
  void report_progress(double f) const {
    if (progress) progress(f);
  }
};

// What an experiment is called and says it does: stated once, given to the base class.
struct ExperimentInfo {
  std::string name;              // stable, e.g. "odometry/sim_corridor"; also the report's file stem
  std::string description;       // one line for `locbench list` and the report
  bool in_default_suite = true;  // part of the suite `locbench run` runs with no argument
  // How to read the results, whatever the run found: the report's first notes, before those the
  // run adds (what it measured, what it could not).
  std::vector<std::string> reading = {};
};

template <typename E>
class Registration;

class Experiment {
 public:
  explicit Experiment(ExperimentInfo info) : info_(std::move(info)) {}
  virtual ~Experiment() = default;
  const std::string& name() const { return info_.name; }
  const std::string& description() const { return info_.description; }
  bool in_default_suite() const { return info_.in_default_suite; }
  // Every option with its default; a user's configuration is merged over it.
  virtual nlohmann::json default_config() const = 0;
  virtual reports::ExperimentResults run(const nlohmann::json& config, const RunOptions& options) const = 0;

  // The results' head: this experiment's name, description, reading notes and the configuration
  // it ran with; the caller adds what it measured.
  reports::ExperimentResults start_results(const nlohmann::json& configuration) const;

  // Tasks for shards and merge (`locbench run --shard K/N`, `locbench merge`). An experiment is
  // split into tasks 0 … task_count − 1, each returning a JSON record, and a summary of all
  // records in task order that equals run(). Monte-Carlo experiments derive from
  // MonteCarloExperiment (monte_carlo.h: one task per run). The defaults here make the whole
  // experiment one task whose record is its results, so shard 1 runs it and the others hold
  // nothing.
  virtual int task_count(const nlohmann::json& config, const RunOptions& options) const;
  // The records of `tasks` (ascending, each < task_count), in that order, canonical (as read
  // back from their JSON text: reports::canonical_record).
  virtual std::vector<nlohmann::json> run_tasks(const nlohmann::json& config, const RunOptions& options,
                                                const std::vector<int>& tasks) const;
  // The results from every task's record, records[i] being task i's.
  virtual reports::ExperimentResults summarise_records(const nlohmann::json& config, const RunOptions& options,
                                                       const std::vector<nlohmann::json>& records) const;

 protected:
  // For experiments registered with their ExperimentInfo (registry.h): Registration gives the
  // info right after construction, so an experiment class need not forward a constructor.
  Experiment() = default;

 private:
  template <typename E>
  friend class Registration;
  ExperimentInfo info_;
};

// All registered experiments (registry.h), sorted by name.
const std::vector<std::unique_ptr<Experiment>>& all_experiments();
// nullptr when no experiment has that name.
const Experiment* find_experiment(const std::string& name);

// Merges `overrides` into `defaults` recursively; a key absent from the defaults or a value of
// another JSON type is a UsageError naming the key.
nlohmann::json merge_config(const nlohmann::json& defaults, const nlohmann::json& overrides,
                            const std::string& path = "");

}  // namespace locbench::experiments
