// Experiment odometry/real_logs: how far raw odometry drifts on real logged data.
// - Freiburg logs (aces, intel, mit_csail): the relative-motion error of raw odometry on the
//   hand-checked relations (Kümmerle et al. 2009), translation and rotation.
// - MRCLAM 6 robots: velocity dead reckoning against Vicon ground truth over fixed windows.
#include <fmt/format.h>

#include <cmath>

#include "core/errors.h"
#include "core/trajectory_error.h"
#include "core/units.h"
#include "datasets/io/odometry_interpolation.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/plot_series.h"
#include "experiment_framework/registry.h"
#include "pipelines/real_log_harness.h"

namespace locbench::experiments::odometry_real_logs {
using io::odometry_trajectory;

const ExperimentInfo kInfo{.name = "odometry/real_logs",
                           .description =
                               "Raw odometry error on real logs: relative-motion error on the Freiburg relations "
                               "and velocity dead reckoning against MRCLAM Vicon ground truth over fixed windows"};

Trajectory truth_trajectory(const Log& log) {
  Trajectory t;
  for (const TruePose& p : log.truth) t.push_back({p.t, p.pose});
  return t;
}

struct Options {
  nlohmann::json datasets = freiburg_and_mrclam_logs();
  double mrclam_window_s = 10.0;
  double local_relation_max_dt_s = 2.0;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("datasets", o.datasets, "", Range{}, "catalog names or user files (real_log_harness.h)");
  v.field("mrclam_window_s", o.mrclam_window_s, "s", positive(), "ground-truth window on MRCLAM");
  v.field("local_relation_max_dt_s", o.local_relation_max_dt_s, "s", positive(), "longest relation counted as local");
}

class OdometryRealLogs final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& c, const RunOptions& options) const override {
    reports::ExperimentResults out = start_results(options_json(c));
    const auto specs = real_log_specs(c.datasets, name());
    for_each_real_log(specs, options, "odometry", out,
                      [&](const RealLogSpec& spec, const LoadedRealLog& loaded, reports::ExperimentResults& res) {
                        const std::string& dataset = spec.name;
                        const Log& log = loaded.log;
                        const Trajectory odom = odometry_trajectory(log);
                        std::vector<Relation> reference = log.relations;
                        std::string method = "odometry_raw", over = "freiburg_relations";
                        std::string suffix;
                        if (reference.empty() && !log.truth.empty()) {
                          reference = window_relations(truth_trajectory(log), c.mrclam_window_s);
                          method = "odometry_velocity";
                          over = "ground_truth_windows";
                          suffix = "_" + std::to_string(static_cast<int>(std::lround(c.mrclam_window_s))) + "s";
                        }
                        const PoseErrors err = relation_error(odom, reference);
                        if (err.translation.empty()) {
                          res.cases.push_back({"odometry/" + dataset, "failed",
                                               "no reference relation falls inside the odometry's time span"});
                          return;
                        }
                        res.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_translation",
                                                                   "m", over, err.translation, false));
                        res.results.push_back(reports::make_metric(method, dataset, "rpe" + suffix + "_rotation", "rad",
                                                                   over, err.rotation, false));
                        for (reports::Plot& p :
                             relative_pose_error_cdfs(dataset, "odometry", {method}, {err.translation}, {err.rotation},
                                                      fmt::format("{} relations ({})", err.translation.size(), over))) {
                          res.plots.push_back(std::move(p));
                        }
                        if (method != "odometry_raw") return;
                        // Freiburg relations mix local motions with loop closures minutes apart; the local
                        // ones (t2 − t1 ≤ local_relation_max_dt_s) show odometry's short-range quality.
                        std::vector<Relation> local;
                        for (const Relation& r : reference) {
                          if (r.t2 - r.t1 <= c.local_relation_max_dt_s) local.push_back(r);
                        }
                        const PoseErrors local_err = relation_error(odom, local);
                        if (local_err.translation.empty()) return;
                        res.results.push_back(reports::make_metric(method, dataset, "rpe_local_translation", "m", over,
                                                                   local_err.translation, false));
                        res.results.push_back(reports::make_metric(method, dataset, "rpe_local_rotation", "rad", over,
                                                                   local_err.rotation, false));
                      });
    return out;
  }
};

const Registration<OdometryRealLogs> odometry_real_logs_registration(kInfo);

}  // namespace locbench::experiments::odometry_real_logs
