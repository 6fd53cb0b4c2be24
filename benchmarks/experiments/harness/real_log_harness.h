#pragma once
// The one loop every real-data experiment shares: a dataset spec (a catalog name, or a user's
// files), then the loaded log with its reference, then one task per dataset.
//
// A configuration's "datasets" is an array whose items are either
//   "aces"                                   a catalog name (datasets/catalog), or
//   {"name": "mine", "log": "my.clf.gz",     a user's log (any load_log spec) with optional
//    "relations": "my.relations",            Freiburg relations and/or TUM ground truth
//    "ground_truth": "my_truth.tum"}         (replacing any the log holds).
// `locbench run EXPERIMENT --log L [--relations R] [--ground-truth G]` is the same as the object
// form with the log file's name as "name" (real_log_cli_override).
//
// Missing catalog data is "skipped" (the data folder is optional); a user's file that is missing
// or malformed is an InputError (exit 2), found as early as setup for a missing file.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "benchmarks/experiments/framework/experiment.h"
#include "core/log.h"
#include "reports/report.h"

namespace locbench::experiments {

struct RealLogSpec {
  std::string name;          // result key ("aces", "mine")
  bool from_catalog = true;  // false: the files below
  std::string log;           // user's log spec (load_log)
  std::string relations;     // optional
  std::string ground_truth;  // optional, TUM
};

// Parses `datasets` (see above). `experiment` prefixes messages. UsageError for an unknown
// catalog name, a malformed item or two items with the same name; InputError naming the file for
// a user's file that does not exist.
std::vector<RealLogSpec> real_log_specs(const nlohmann::json& datasets, const std::string& experiment);

// The catalog's real logs as a configuration's default "datasets": the three Freiburg logs with
// scans and relations, and those with the five MRCLAM robots (odometry and Vicon truth).
inline nlohmann::json freiburg_logs() { return {"aces", "intel", "mit_csail"}; }
inline nlohmann::json freiburg_and_mrclam_logs() {
  return {"aces",           "intel",          "mit_csail",      "mrclam6_robot1",
          "mrclam6_robot2", "mrclam6_robot3", "mrclam6_robot4", "mrclam6_robot5"};
}

// The names of `specs`, in order.
std::vector<std::string> real_log_names(const std::vector<RealLogSpec>& specs);

struct LoadedRealLog {
  std::string status = "ok";  // "ok" | "skipped" (catalog data absent) | "failed" (catalog
                              // data unreadable)
  std::string reason;
  Log log;
  reports::DatasetRef dataset;  // name, path, checksum, records, duration
};

// Loads one spec under `data_root`. Catalog data: absent → "skipped", InputError → "failed"
// (reason = its message). A user's files: InputError propagates (exit 2).
LoadedRealLog load_real_log(const RealLogSpec& spec, const std::filesystem::path& data_root);

// The loop of a non-Monte-Carlo real-data experiment: for each spec, report progress, load it,
// turn skipped/failed into a case "<case_prefix>/<name>" of `out`, else add its DatasetRef to
// out.datasets and call `run(spec, loaded, out)`.
void for_each_real_log(
    const std::vector<RealLogSpec>& specs, const RunOptions& options, const std::string& case_prefix,
    reports::ExperimentResults& out,
    const std::function<void(const RealLogSpec&, const LoadedRealLog&, reports::ExperimentResults&)>& run);

// The configuration override `locbench run --log/--relations/--ground-truth` applies:
// {"datasets": [{"name": <log file name without extensions>, "log": …, …}]}. Empty log → nullopt.
std::optional<nlohmann::json> real_log_cli_override(const std::string& log, const std::string& relations,
                                                    const std::string& ground_truth);

// True when an experiment's configuration takes real-log dataset specs (has "datasets").
bool takes_real_logs(const nlohmann::json& default_config);

}  // namespace locbench::experiments
