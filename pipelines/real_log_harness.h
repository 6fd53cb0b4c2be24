#pragma once
// The one loop every real-data experiment shares: a dataset spec (a catalog name, or a user's
// files), then the loaded log with its reference, then one task per dataset.
//
// A configuration's "datasets" is an array whose items are either
//   "aces"                                   a catalog name (datasets/catalog), or
//   {"name": "mine", "log": "my.clf.gz",     a user's log (any load_log spec, e.g. an MRCLAM
//    "relations": "my.relations",            folder "…/MRCLAM_Dataset6#robot2") with optional
//    "ground_truth": "my_truth.tum",         Freiburg relations, TUM ground truth, a landmark
//    "landmark_map": "map.txt",              map and landmark observations (datasets/FORMAT.md;
//    "landmark_observations": "obs.txt"}     each replacing what the log holds; attach_landmark_files).
// `locbench run EXPERIMENT --log L [--relations R] [--ground-truth G] [--landmark-map M]
// [--landmark-observations O]` is the same as the object form with the log file's name as
// "name" (real_log_cli_override).
//
// Missing catalog data is "skipped" (the data folder is optional); a user's file that is missing
// or malformed is an InputError (exit 2), found as early as setup for a missing file.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/log.h"
#include "experiment_framework/experiment.h"
#include "reports/report.h"

namespace locbench::experiments {

struct RealLogSpec {
  std::string name;                   // result key ("aces", "mine")
  bool from_catalog = true;           // false: the files below
  std::string log;                    // user's log spec (load_log)
  std::string relations;              // optional
  std::string ground_truth;           // optional, TUM
  std::string landmark_map;           // optional: id x y [sigma_x sigma_y]
  std::string landmark_observations;  // optional: t id range bearing
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
// (reason = its message); read once per process and copied to each caller (the experiments of a
// suite share the catalog's logs), read again when the log's file changes. A user's files: read
// at every call; InputError propagates (exit 2).
LoadedRealLog load_real_log(const RealLogSpec& spec, const std::filesystem::path& data_root);

// Copies what a load gave (status, reason, and the dataset's path, checksum and record count)
// into the fields of the same names of a Monte-Carlo experiment's per-task record.
template <class Record>
void record_load(const LoadedRealLog& loaded, Record& rec) {
  rec.status = loaded.status;
  rec.reason = loaded.reason;
  rec.path = loaded.dataset.path;
  rec.checksum = loaded.dataset.checksum;
  rec.records = loaded.dataset.records;
}

// The loop of a non-Monte-Carlo real-data experiment: for each spec, report progress, load it,
// turn skipped/failed into a case "<case_prefix>/<name>" of `out`, else add its DatasetRef to
// out.datasets and call `run(spec, loaded, out)`.
void for_each_real_log(
    const std::vector<RealLogSpec>& specs, const RunOptions& options, const std::string& case_prefix,
    reports::ExperimentResults& out,
    const std::function<void(const RealLogSpec&, const LoadedRealLog&, reports::ExperimentResults&)>& run);

// The configuration override `locbench run --log/--relations/--ground-truth/--landmark-map/
// --landmark-observations` applies: {"datasets": [{"name": <log file name without extensions,
// "_robotN" for an MRCLAM folder#robotN>, "log": …, …}]} (empty paths left out). Empty log →
// nullopt.
std::optional<nlohmann::json> real_log_cli_override(const std::string& log, const std::string& relations,
                                                    const std::string& ground_truth,
                                                    const std::string& landmark_map = {},
                                                    const std::string& landmark_observations = {});

// True when an experiment's configuration takes real-log dataset specs (has "datasets").
bool takes_real_logs(const nlohmann::json& default_config);

}  // namespace locbench::experiments
