// Experiment odometry/real_logs: how far raw odometry drifts on real logged data.
// - Freiburg logs (aces, intel, mit_csail): the relative-motion error of raw odometry on the
//   hand-checked relations (Kümmerle et al. 2009), translation and rotation.
// - MRCLAM 6 robots: velocity dead reckoning against Vicon ground truth over fixed windows.
#include <cmath>

#include "algorithms/core/errors.h"
#include "algorithms/core/trajectory_error.h"
#include "benchmarks/experiments/experiment.h"
#include "benchmarks/experiments/experiments_list.h"
#include "datasets/catalog/dataset_catalog.h"
#include "datasets/io/odometry_interpolation.h"
#include "reports/checksum.h"

namespace locbench::experiments {
namespace {

Trajectory truth_trajectory(const Log& log) {
  Trajectory t;
  for (const TruePose& p : log.truth) t.push_back({p.t, p.pose});
  return t;
}

class OdometryRealLogs final : public Experiment {
 public:
  std::string name() const override { return "odometry/real_logs"; }
  std::string description() const override {
    return "Raw odometry error on real logs: relative-motion error on the Freiburg relations "
           "and velocity dead reckoning against MRCLAM Vicon ground truth over fixed windows";
  }
  nlohmann::json default_config() const override {
    return {{"datasets", {"aces", "intel", "mit_csail", "mrclam6_robot1", "mrclam6_robot2",
                          "mrclam6_robot3", "mrclam6_robot4", "mrclam6_robot5"}},
            {"mrclam_window_s", 10.0},
            {"local_relation_max_dt_s", 2.0}};
  }

  reports::ExperimentResults run(const nlohmann::json& config,
                                 const RunOptions& options) const override {
    reports::ExperimentResults out;
    out.experiment = name();
    out.description = description();
    out.configuration = config;
    const auto names = config.at("datasets").get<std::vector<std::string>>();
    const double window = config.at("mrclam_window_s").get<double>();
    const double local_dt = config.at("local_relation_max_dt_s").get<double>();
    if (!(window > 0.0)) throw UsageError("odometry/real_logs: mrclam_window_s must be > 0");
    std::size_t done = 0;
    for (const std::string& dataset : names) {
      options.report_progress(static_cast<double>(done++) / static_cast<double>(names.size()));
      const DatasetEntry* entry = find_dataset(dataset);
      if (!entry) throw UsageError("odometry/real_logs: unknown dataset \"" + dataset + "\"");
      const std::string path = (options.data_root / entry->path).string();
      if (!std::filesystem::exists(path.substr(0, path.find('#')))) {
        out.cases.push_back({"odometry/" + dataset, "skipped",
                             "dataset not found at " + path + " (set LOCBENCH_DATA)"});
        continue;
      }
      Log log;
      try {
        log = load_catalog_dataset(*entry, options.data_root);
      } catch (const InputError& e) {
        out.cases.push_back({"odometry/" + dataset, "failed", e.what()});
        continue;
      }
      const auto [t0, t1] = log.time_span();
      const std::string file = path.substr(0, path.find('#'));
      out.datasets.push_back({dataset, path, reports::file_checksum(file), log.record_count(),
                              t1 - t0});
      const Trajectory odom = odometry_trajectory(log);
      std::vector<Relation> reference = log.relations;
      std::string method = "odometry_raw", over = "freiburg_relations";
      std::string suffix;
      if (reference.empty() && !log.truth.empty()) {
        reference = window_relations(truth_trajectory(log), window);
        method = "odometry_velocity";
        over = "ground_truth_windows";
        suffix = "_" + std::to_string(static_cast<int>(std::lround(window))) + "s";
      }
      const PoseErrors err = relation_error(odom, reference);
      if (err.translation.empty()) {
        out.cases.push_back({"odometry/" + dataset, "failed",
                             "no reference relation falls inside the odometry's time span"});
        continue;
      }
      out.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_translation",
                                                 "m", over, err.translation, false));
      out.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_rotation",
                                                 "rad", over, err.rotation, false));
      if (method != "odometry_raw") continue;
      // Freiburg relations mix local motions with loop closures minutes apart; the local
      // ones (t2 − t1 ≤ local_relation_max_dt_s) show odometry's short-range quality.
      std::vector<Relation> local;
      for (const Relation& r : reference) {
        if (r.t2 - r.t1 <= local_dt) local.push_back(r);
      }
      const PoseErrors local_err = relation_error(odom, local);
      if (local_err.translation.empty()) continue;
      out.results.push_back(reports::make_metric(method, dataset, "rpe_local_translation", "m",
                                                 over, local_err.translation, false));
      out.results.push_back(reports::make_metric(method, dataset, "rpe_local_rotation", "rad",
                                                 over, local_err.rotation, false));
    }
    options.report_progress(1.0);
    return out;
  }
};

}  // namespace

std::unique_ptr<Experiment> make_odometry_real_logs() {
  return std::make_unique<OdometryRealLogs>();
}

}  // namespace locbench::experiments
