// Experiment noise/real_logs: are the odometry noise models consistent on real odometry?
// None of our real logs has a compass, so the compass-aided filters cannot run on them; what can
// be checked is the prediction half: integrate the logged odometry over each reference interval
// (Freiburg .relations; MRCLAM Vicon over fixed windows), propagate its covariance with a noise
// model (Σ' = F Σ Fᵀ + Q per odometry record), and test the relative-pose error against it by
// its NEES (3 dof). Body increments are turned into wheel travel with a virtual track.
#include <fmt/format.h>

#include <cmath>

#include "algorithms/filters/consistency.h"
#include "algorithms/filters/odometry_noise_model.h"
#include "core/dead_reckoning.h"
#include "core/diff_drive_odometry.h"
#include "core/errors.h"
#include "core/statistics.h"
#include "core/trajectory_error.h"
#include "datasets/io/odometry_interpolation.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/options_experiment.h"
#include "experiment_framework/registry.h"
#include "pipelines/real_log_harness.h"

namespace locbench::experiments::noise_real_logs {
using io::odometry_trajectory;
using locbench::filters::adaptive_process_noise, locbench::filters::average_chi_square_interval,
    locbench::filters::ChiSquareInterval, locbench::filters::nees, locbench::filters::OdometryNoiseOptions,
    locbench::filters::pose_nees;

const ExperimentInfo kInfo{
    .name = "noise/real_logs",
    .description =
        "Consistency (NEES) of the odometry noise models on real odometry: Freiburg against "
        ".relations, MRCLAM against Vicon windows (no compass in any real log)",
    .reading = {"Not evaluable on real data: the compass-aided filters (fixed-Q EKF, adaptive model, "
                "Sage–Husa AEKF, VB-AKF) and the slip detector — none of our real logs has a compass; "
                "the encoder-quantization model — the real logs carry odometry poses or velocities, not "
                "ticks (BreezySLAM's ticks have no reference). Here the models' prediction covariance is "
                "checked against reference relative motions only. Read the medians: the adaptive model's "
                "Q (eq. 4.43–4.44) is diagonal with var(w_d)·cos²(θ) and var(w_d)·sin²(θ), so for motion "
                "along a world axis it has no lateral variance; such relations get a near-singular "
                "covariance and an enormous NEES, which dominates the means."}};

enum class Model { kAdaptive, kFixedQ };

// NEES of one relation: odometry integrated from t1 to t2 in the frame at t1, covariance
// propagated with the model; nullopt if the interval has no odometry inside.
std::optional<double> relation_nees(const Trajectory& odom, const Relation& r, Model model,
                                    const OdometryNoiseOptions& adaptive, const Eigen::Vector3d& fixed_q,
                                    double track) {
  const auto a = odom.pose_at(r.t1);
  const auto b = odom.pose_at(r.t2);
  if (!a || !b) return std::nullopt;
  std::vector<Pose2> poses{*a};
  for (const StampedPose& p : odom.poses()) {
    if (p.t > r.t1 && p.t < r.t2) poses.push_back(p.pose);
  }
  poses.push_back(*b);
  Pose2 x;  // in the frame at t1
  Matrix3 P = Matrix3::Zero();
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const Pose2 d = between(poses[i - 1], poses[i]);
    const double dD = std::hypot(d.x, d.y) * (d.x < 0 ? -1.0 : 1.0);
    const WheelDisplacement u{dD - 0.5 * track * d.theta, dD + 0.5 * track * d.theta};
    const Matrix3 F = odometry_jacobian_pose(x, u, track);
    const Matrix3 Q =
        model == Model::kAdaptive ? adaptive_process_noise(adaptive, x.theta, u, track) : Matrix3(fixed_q.asDiagonal());
    P = F * P * F.transpose() + Q;
    x = odometry_step(x, u, track);
  }
  return pose_nees(r.delta, Eigen::Vector3d(x.x, x.y, x.theta), P);
}

// The adaptive model's parameters, the same for both wheels.
struct AdaptiveOptions {
  double k = 0.005;
  double sigma_m = 0.005;
};
template <class V>
void visit_fields(V& v, AdaptiveOptions& o) {
  v.field("k", o.k, "", non_negative(), "k_left = k_right of the adaptive model (eq. 4.36–4.44)");
  v.field("sigma_m", o.sigma_m, "m", non_negative(), "σ_left = σ_right of the adaptive model");
}
LOCBENCH_EXPERIMENT_OPTIONS(AdaptiveOptions)

struct Options {
  nlohmann::json datasets = freiburg_and_mrclam_logs();
  double relation_max_duration_s = 10.0;
  double mrclam_window_s = 2.0;
  double virtual_track_m = 0.5;
  AdaptiveOptions adaptive;
  Eigen::Vector3d fixed_q_diag{6.33e-6, 6.33e-6, 2.0 * deg(1.0) * deg(1.0)};
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("datasets", o.datasets, "", Range{}, "catalog names or user files (real_log_harness.h)");
  v.field("relation_max_duration_s", o.relation_max_duration_s, "s", positive(), "longest Freiburg relation evaluated");
  v.field("mrclam_window_s", o.mrclam_window_s, "s", positive(), "ground-truth window on MRCLAM");
  v.field("virtual_track_m", o.virtual_track_m, "m", positive(),
          "track of the virtual differential drive the odometry is split into");
  v.nested("adaptive", o.adaptive, "the adaptive noise model");
  v.field("fixed_q_diag", o.fixed_q_diag, "m², m², rad²", non_negative(), "diagonal of the fixed Q");
}

class NoiseRealLogs final : public OptionsExperiment<Options> {
 public:
  reports::ExperimentResults run_with(const Options& c, const RunOptions& options) const override {
    reports::ExperimentResults out = start_results(options_json(c));
    OdometryNoiseOptions adaptive;
    adaptive.k_left = adaptive.k_right = c.adaptive.k;
    adaptive.sigma_left = adaptive.sigma_right = c.adaptive.sigma_m;
    const auto specs = real_log_specs(c.datasets, name());
    const ChiSquareInterval band = average_chi_square_interval(3, 1, 0.95);
    for_each_real_log(specs, options, "noise", out,
                      [&](const RealLogSpec& spec, const LoadedRealLog& loaded, reports::ExperimentResults& res) {
                        const std::string& ds = spec.name;
                        const Log& log = loaded.log;
                        const Trajectory odom = odometry_trajectory(log);
                        std::vector<Relation> rel;
                        if (!log.relations.empty()) {
                          for (const Relation& r : log.relations) {
                            if (r.t2 - r.t1 <= c.relation_max_duration_s) rel.push_back(r);
                          }
                        } else {
                          Trajectory truth;
                          for (const TruePose& p : log.truth) truth.push_back({p.t, p.pose});
                          rel = window_relations(truth, c.mrclam_window_s);
                        }
                        const char* model_names[2] = {"adaptive_noise_model", "fixed_q"};
                        for (int m = 0; m < 2; ++m) {
                          std::vector<double> nees;
                          std::size_t inside = 0;
                          for (const Relation& r : rel) {
                            const auto v = relation_nees(odom, r, m == 0 ? Model::kAdaptive : Model::kFixedQ, adaptive,
                                                         c.fixed_q_diag, c.virtual_track_m);
                            if (!v || !std::isfinite(*v)) continue;
                            nees.push_back(*v);
                            if (band.contains(*v)) ++inside;
                          }
                          if (nees.empty()) continue;
                          res.results.push_back(reports::make_metric(model_names[m], ds, "relation_nees", "",
                                                                     "reference_relations", nees, false));
                          res.notes.push_back(fmt::format(
                              "{} on {}: mean NEES {:.3g} (3 for a consistent model), median {:.3g}; {:.0f}% of {} "
                              "relations inside the 95% band [{:.3g}, {:.3g}].",
                              model_names[m], ds, mean(nees), quantile(nees, 0.5),
                              100.0 * static_cast<double>(inside) / static_cast<double>(nees.size()), nees.size(),
                              band.lower, band.upper));
                        }
                      });
    return out;
  }
};

const Registration<NoiseRealLogs> noise_real_logs_registration(kInfo);

}  // namespace locbench::experiments::noise_real_logs
