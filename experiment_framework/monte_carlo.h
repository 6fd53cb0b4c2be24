#pragma once
// Monte-Carlo experiments that run on all cores and in shards on several machines, with results
// independent of both. An experiment is split into
//   setup(config, plan)               once per process: options, shared pre-computation;
//   run_task(setup, plan, k)          task k (normally Monte-Carlo run k) → a JSON record; called
//                                     concurrently, possibly in another process than summarise;
//   summarise(setup, plan, records)   records[k] of every task, in task order → the results.
// run() and the shard/merge entry points of Experiment are implemented here from these three.
// How to write one: docs/sharding.md.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <vector>

#include "core/errors.h"
#include "core/rng.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/experiment_options.h"
#include "experiment_framework/parallel_tasks.h"
#include "reports/shard_report.h"

namespace locbench::experiments {

// What every step of a Monte-Carlo experiment may depend on besides the configuration.
struct McPlan {
  std::uint64_t seed = 1;  // base seed
  int runs = 1;            // Monte-Carlo runs: --runs, else the configuration's "runs" (≥ 1)
  std::filesystem::path data_root;
  int threads = 1;  // for parallel_tasks inside run_task or summarise; never changes a result
  // The seed of Monte-Carlo run k (recorded in the report's seeds).
  std::uint64_t run_seed(int k) const { return Rng::derive_seed(seed, static_cast<std::uint64_t>(k)); }
};

template <typename Options, typename Setup>
class MonteCarloExperiment : public Experiment {
 public:
  using Experiment::Experiment;
  // The options' defaults, as JSON.
  nlohmann::json default_config() const final { return options_json(defaults()); }
  // Deterministic from (options, plan); must not depend on plan.threads.
  virtual Setup setup(const Options& options, const McPlan& plan) const = 0;
  // Number of tasks; a sweep may use runs × cases.
  virtual int tasks(const Setup&, const McPlan& plan) const { return plan.runs; }
  // Thread-safe and pure: depends only on (setup, plan.seed, plan.runs, task).
  virtual nlohmann::json run_task(const Setup& setup, const McPlan& plan, int task) const = 0;
  // records.size() == task_count; must not depend on plan.threads.
  virtual reports::ExperimentResults summarise(const Setup& setup, const McPlan& plan,
                                               const std::vector<nlohmann::json>& records) const = 0;

  reports::ExperimentResults run(const nlohmann::json& config, const RunOptions& options) const final {
    const Options o = read(config);
    const McPlan p = plan(o, options);
    const Setup s = setup(o, p);
    std::vector<int> all(static_cast<std::size_t>(tasks(s, p)));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    // Summarised in this process: the records need not read back from their text.
    const std::vector<nlohmann::json> records = records_of(s, p, options, all, Records::kAsBuilt);
    reports::ExperimentResults out = summarise(s, p, records);
    options.report_progress(1.0);
    return out;
  }

  int task_count(const nlohmann::json& config, const RunOptions& options) const final {
    const Options o = read(config);
    const McPlan p = plan(o, options);
    return tasks(setup(o, p), p);
  }

  std::vector<nlohmann::json> run_tasks(const nlohmann::json& config, const RunOptions& options,
                                        const std::vector<int>& which) const final {
    const Options o = read(config);
    const McPlan p = plan(o, options);
    const Setup s = setup(o, p);
    const int n = tasks(s, p);
    for (int t : which) {
      if (t < 0 || t >= n) {
        throw UsageError(name() + ": task " + std::to_string(t) + " outside 0…" + std::to_string(n - 1));
      }
    }
    std::vector<nlohmann::json> records = records_of(s, p, options, which, Records::kCanonical);
    options.report_progress(1.0);
    return records;
  }

  reports::ExperimentResults summarise_records(const nlohmann::json& config, const RunOptions& options,
                                               const std::vector<nlohmann::json>& records) const final {
    const Options o = read(config);
    const McPlan p = plan(o, options);
    const Setup s = setup(o, p);
    if (static_cast<int>(records.size()) != tasks(s, p)) {
      throw UsageError(name() + ": " + std::to_string(records.size()) + " records for " + std::to_string(tasks(s, p)) +
                       " tasks");
    }
    return summarise(s, p, records);
  }

 protected:
  // The defaults of the options (Options{} unless the experiment's depend on its constructor).
  virtual Options defaults() const { return Options{}; }
  // The configuration a report records: the options, with the runs this process ran.
  static nlohmann::json recorded(Options o, const McPlan& p) {
    o.runs = p.runs;
    return options_json(o);
  }

 private:
  Options read(const nlohmann::json& config) const { return read_options(config, name(), defaults()); }
  McPlan plan(const Options& o, const RunOptions& options) const {
    McPlan p;
    p.seed = options.seed;
    p.runs = options.runs.value_or(o.runs);
    if (p.runs < 1) throw UsageError(name() + ": runs must be ≥ 1");
    p.data_root = options.data_root;
    p.threads = options.threads;
    return p;
  }
  // kCanonical: each record as it reads back from a shard file's text (reports::canonical_record);
  // kAsBuilt: as run_task returned it, which summarises to the same bytes.
  enum class Records { kCanonical, kAsBuilt };
  // Runs `tasks` on options.threads threads; records by position.
  std::vector<nlohmann::json> records_of(const Setup& s, const McPlan& p, const RunOptions& options,
                                         const std::vector<int>& which, Records form) const {
    std::vector<nlohmann::json> records(which.size());
    std::atomic<std::size_t> done{0};
    std::mutex progress_mutex;
    options.report_progress(0.0);
    parallel_tasks(options.threads, which.size(), [&](std::size_t i) {
      nlohmann::json record = run_task(s, p, which[i]);
      records[i] = form == Records::kCanonical ? reports::canonical_record(record) : std::move(record);
      const std::size_t d = ++done;
      if (options.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        options.report_progress(static_cast<double>(d) / static_cast<double>(which.size()));
      }
    });
    return records;
  }
};

}  // namespace locbench::experiments
