// Experiment odometry/real_logs: how far raw odometry drifts on real logged data.
// - Freiburg logs (aces, intel, mit_csail): the relative-motion error of raw odometry on the
//   hand-checked relations (Kümmerle et al. 2009), translation and rotation.
// - MRCLAM 6 robots: velocity dead reckoning against Vicon ground truth over fixed windows.
#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "core/trajectory_error.h"
#include "core/units.h"
#include "benchmarks/experiments/framework/experiment.h"
#include "benchmarks/experiments/framework/plot_series.h"
#include "benchmarks/experiments/framework/registry.h"
#include "benchmarks/experiments/harness/real_log_harness.h"
#include "datasets/io/odometry_interpolation.h"

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
    reports::ExperimentResults out = start_results(config);
    const auto specs = real_log_specs(config.at("datasets"), name());
    const double window = config.at("mrclam_window_s").get<double>();
    const double local_dt = config.at("local_relation_max_dt_s").get<double>();
    if (!(window > 0.0)) throw UsageError("odometry/real_logs: mrclam_window_s must be > 0");
    for_each_real_log(specs, options, "odometry", out,
                      [&](const RealLogSpec& spec, const LoadedRealLog& loaded,
                          reports::ExperimentResults& res) {
      const std::string& dataset = spec.name;
      const Log& log = loaded.log;
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
        res.cases.push_back({"odometry/" + dataset, "failed",
                             "no reference relation falls inside the odometry's time span"});
        return;
      }
      res.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_translation",
                                                 "m", over, err.translation, false));
      res.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_rotation",
                                                 "rad", over, err.rotation, false));
      for (reports::Plot& p : relative_pose_error_cdfs(dataset, "odometry", {method}, {err.translation},
                                                       {err.rotation},
                                                       fmt::format("{} relations ({})", err.translation.size(), over))) {
        res.plots.push_back(std::move(p));
      }
      if (method != "odometry_raw") return;
      // Freiburg relations mix local motions with loop closures minutes apart; the local
      // ones (t2 − t1 ≤ local_relation_max_dt_s) show odometry's short-range quality.
      std::vector<Relation> local;
      for (const Relation& r : reference) {
        if (r.t2 - r.t1 <= local_dt) local.push_back(r);
      }
      const PoseErrors local_err = relation_error(odom, local);
      if (local_err.translation.empty()) return;
      res.results.push_back(reports::make_metric(method, dataset, "rpe_local_translation", "m",
                                                 over, local_err.translation, false));
      res.results.push_back(reports::make_metric(method, dataset, "rpe_local_rotation", "rad",
                                                 over, local_err.rotation, false));
    });
    return out;
  }
};

const Registration<OdometryRealLogs> odometry_real_logs_registration;

}  // namespace
}  // namespace locbench::experiments
