#pragma once
// Shared by the global-localization experiments and `locbench localize`: a log as one step per
// laser scan (odometry pose, scan, reference pose), a kidnapping spliced from two logs, the four
// localizers behind one interface (MCL and grid Markov from baselines/global; the chapter-6 EKF
// with EAP matches and the slides' line-feature Kalman localizer, both tracking from a known
// start), convergence and tracking metrics, and a line map built from a log's own scans.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/line_map.h"
#include "core/log.h"
#include "core/option_fields.h"
#include "core/pose2.h"
#include "core/scan.h"
#include "reports/report.h"

namespace locbench::experiments::global {

struct ScanStep {
  double t = 0.0;
  Pose2 odometry;                  // odometry pose at the scan (odometry frame)
  const Scan* scan = nullptr;      // points into the log (or a copy kept by the caller)
  std::optional<Pose2> reference;  // truth (simulated) or the map frame's reference pose
};

// One step per scan that has odometry at its stamp (interpolated ODOM; FLASER odom poses for
// logs without ODOM); reference = interpolated TRUEPOS when the log has it.
std::vector<ScanStep> scan_steps(const Log& log);

// `b` after `a`: b's odometry re-expressed to continue from a's last odometry pose and its times
// shifted to follow a — the robot is carried to b's start without the odometry noticing.
std::vector<ScanStep> splice_kidnapping(std::vector<ScanStep> a, const std::vector<ScanStep>& b);

// Method names: "mcl", "grid_markov" (global, start unknown), "ekf_eap", "kalman_line_features"
// (trackers: need `start`).
inline const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names{"mcl", "grid_markov", "ekf_eap", "kalman_line_features"};
  return names;
}
bool is_global_method(const std::string& name);

class Localizer {
 public:
  virtual ~Localizer() = default;
  virtual void step(const ScanStep& s) = 0;
  virtual Pose2 pose() const = 0;
  virtual std::size_t memory_bytes() const = 0;
  // Particles for MCL, cells for the grid, 1 for the Kalman filters.
  virtual std::size_t hypotheses() const = 0;
};

// Every method's options with defaults: {"mcl": …, "grid_markov": …, "ekf_eap": {"eap", "tracker"},
// "kalman_line_features": {"split_and_merge", "line_kalman"}, "wheelbase": 0.33}.
nlohmann::json default_method_options();
// UsageError for an unknown name or bad options; a tracker without `start` is a UsageError.
std::unique_ptr<Localizer> make_localizer(const std::string& name, const LineMap& map, const nlohmann::json& options,
                                          const std::optional<Pose2>& start, std::uint64_t seed);

// Estimated pose at every step.
std::vector<Pose2> run_localizer(Localizer& l, const std::vector<ScanStep>& steps, std::size_t begin, std::size_t end);

struct ConvergenceCriterion {
  double position = 0.5;  // [m]
  double heading = 0.35;  // [rad]
};

// The options global/sim and global/real_logs share: the methods compared, their options and
// when an estimate counts as converged.
struct MethodComparisonOptions {
  std::vector<std::string> methods = method_names();
  nlohmann::json method_options = default_method_options();  // make_localizer's
  double convergence_position_m = 0.5;
  double convergence_heading_rad = 0.35;
  ConvergenceCriterion criterion() const { return {convergence_position_m, convergence_heading_rad}; }
};
template <class V>
void visit_method_comparison_fields(V& v, MethodComparisonOptions& o) {
  v.field("methods", o.methods, "", Range{}, "the localizers compared (method_names())");
  v.field("method_options", o.method_options, "", Range{}, "each method's options (make_localizer)");
  v.field("convergence_position_m", o.convergence_position_m, "m", positive(),
          "converged: position error at most this");
  v.field("convergence_heading_rad", o.convergence_heading_rad, "rad", positive(),
          "converged: heading error at most this");
}
// Index (relative to `begin`) of the first step from which the estimate stays within the
// criterion of the reference until `end`; nullopt when it never settles.
std::optional<std::size_t> converged_from(const std::vector<Pose2>& est, const std::vector<ScanStep>& steps,
                                          std::size_t begin, std::size_t end, const ConvergenceCriterion& c);
// Distance travelled by the reference between steps a and b.
double path_length(const std::vector<ScanStep>& steps, std::size_t a, std::size_t b);

// RMS position [m] and heading [rad] error against the reference over steps [begin, end): the
// tracking accuracy of a localizer that has converged by `begin`.
struct TrackingRms {
  double position = 0.0;
  double heading = 0.0;
};
TrackingRms tracking_rms(const std::vector<Pose2>& est, const std::vector<ScanStep>& steps, std::size_t begin,
                         std::size_t end);

// One method's samples over the runs (a value per run that has it).
struct MethodRunSamples {
  std::vector<double> converged, time_to_convergence, distance_to_convergence;  // from the start
  std::vector<double> rms_position, rms_heading;                                // tracking
  std::vector<double> recovered, recovery_time, recovery_distance;              // after the kidnap
  std::vector<double> memory;                                                   // [bytes]
};
// Adds the method's results over Monte-Carlo runs to `out` (convergence only for the global
// methods; a metric without samples is left out).
void add_method_metrics(reports::ExperimentResults& out, const std::string& method, const std::string& dataset,
                        const MethodRunSamples& s);

// A line map from the log's own scans: split-and-merge lines of every `every`-th scan in
// [t0, t1], placed with the odometry pose at the scan (the map's frame is the odometry's).
LineMap map_from_scans(const std::vector<ScanStep>& steps, double t0, double t1, int every);

}  // namespace locbench::experiments::global
