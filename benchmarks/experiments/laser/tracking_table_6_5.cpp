// Experiment laser/tracking_table_6_5: position tracking in a corridor (§6.6.2, Table 6.5).
// A Pioneer 2-DXe (true wheels off the nominal ones by 0.1% each and 2 mm in wheelbase) drives
// 10 m straight at 200 mm/s along a 1.8 m corridor, encoders and LMS 200 at 5 Hz. Per
// Monte-Carlo run, the same log is tracked by
//   odometry           dead reckoning with the nominal model;
//   ekf_eap            the chapter-6 EKF (eq. 6.39–6.42): EAP matches → weighted-LS heading and
//                      point-to-point position → full-pose or heading-only update;
//   ekf_split_and_merge the same EKF fed by the split-and-merge matcher instead of EAP;
//   kalman_line_features the slides' Kalman localizer: split-and-merge lines in the robot frame
//                      as (α, r) observations, validation gate, stacked update (baseline).
// E_error (6.43) = distance between the true and estimated end positions.
#include <fmt/format.h>

#include <cmath>

#include "algorithms/laser/eap_matcher.h"
#include "algorithms/pose_correction/ekf_tracker.h"
#include "baselines/laser/extract_then_match.h"
#include "baselines/laser/options_json.h"
#include "baselines/localization/line_feature_kalman_localizer.h"
#include "baselines/localization/line_observation.h"
#include "core/checksum.h"
#include "core/diff_drive_odometry.h"
#include "core/statistics.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"
#include "pipelines/scenario_option.h"
#include "reports/findings.h"
#include "reports/published_rows.h"

namespace locbench::experiments::laser_tracking_table_6_5 {

const ExperimentInfo kInfo{.name = "laser/tracking_table_6_5",
                           .description =
                               "Corridor tracking, 200 mm/s, 5 Hz, 10 m (Table 6.5): chapter-6 EKF with EAP or "
                               "split-and-merge matches vs the slides' line-feature Kalman localizer vs odometry"};

enum Method { kOdometry, kEkfEap, kEkfSplitMerge, kLineKalman, kMethods };
const char* const kMethodNames[kMethods] = {"odometry", "ekf_eap", "ekf_split_and_merge", "kalman_line_features"};
constexpr double kTable65[10] = {62.07, 55.48, 71.42, 66.24, 48.69, 81.46, 70.28, 53.48, 67.69, 53.43};

sim::Scenario corridor_at_5_hz() {
  sim::Scenario s = sim::preset("corridor_laser");
  s.encoders.timing.rate = 5.0;  // §6.6.2: encoders and laser both at 5 Hz
  return s;
}

struct Options {
  int runs = 10;
  sim::Scenario scenario = corridor_at_5_hz();
  laser::EapOptions eap;
  baselines::laser::SplitAndMergeMatcherOptions split_and_merge;
  pose_correction::EkfTrackerOptions tracker;
  baselines::localization::LineFeatureKalmanOptions line_kalman;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.coded("scenario", o.scenario, scenario_json, scenario_option, "the simulated corridor run (datasets/sim)");
  v.nested("eap", o.eap, "EAP matcher of ekf_eap");
  v.coded("split_and_merge", o.split_and_merge, adl_json<baselines::laser::SplitAndMergeMatcherOptions>,
          adl_from_json<baselines::laser::SplitAndMergeMatcherOptions>, "split-and-merge matcher");
  v.nested("tracker", o.tracker, "the chapter-6 EKF tracker");
  v.nested("line_kalman", o.line_kalman, "the slides' line-feature Kalman localizer");
}

struct Setup {
  sim::Scenario scenario;
  laser::EapOptions eap;
  baselines::laser::SplitAndMergeMatcherOptions split_and_merge;
  pose_correction::EkfTrackerOptions tracker;
  baselines::localization::LineFeatureKalmanOptions line_kalman;
  nlohmann::json configuration;
};

struct Record {
  std::vector<double> final_position_error;          // [method] [m]
  std::vector<double> final_heading_error;           // [method] [rad]
  std::vector<double> rms_position_error;            // [method] over the scans [m]
  double full_updates = 0.0, heading_updates = 0.0;  // ekf_eap
  std::size_t records = 0;
  double duration = 0.0;
  // Run 0 only: x and y of the truth and of each method at every scan (for the report's chart).
  std::vector<std::vector<double>> path_x, path_y;  // [truth, method…][scan]
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Record, final_position_error, final_heading_error, rms_position_error, full_updates,
                                   heading_updates, records, duration, path_x, path_y)

class LaserTracking final : public MonteCarloExperiment<Options, Setup> {
 public:
  Setup setup(const Options& o, const McPlan& plan) const override {
    if (o.scenario.laser.timing.rate <= 0 || o.scenario.encoders.timing.rate <= 0) {
      throw UsageError(name() + ": the scenario needs encoders and a laser");
    }
    return {o.scenario, o.eap, o.split_and_merge, o.tracker, o.line_kalman, recorded(o, plan)};
  }

  nlohmann::json run_task(const Setup& s, const McPlan& plan, int k) const override {
    const sim::SimulationResult r = sim::simulate(s.scenario, plan.run_seed(k));
    const Trajectory truth = sim::true_trajectory(r);
    const NominalModel model = s.scenario.robot.params().nominal_model();
    const auto& enc = r.log.encoders;
    const auto& scans = r.log.laser;
    const Pose2 start = *truth.pose_at(enc.front().t);

    const laser::EapMatcher eap(s.eap);
    const baselines::laser::SplitAndMergeMatcher sm(s.split_and_merge);
    pose_correction::EkfTracker ekf_eap(s.tracker, model.wheelbase, start);
    pose_correction::EkfTracker ekf_sm(s.tracker, model.wheelbase, start);
    baselines::localization::LineFeatureKalmanLocalizer line_kf(s.line_kalman, model.wheelbase, start);
    Pose2 odo = start;
    Record rec;
    rec.records = r.log.record_count();
    rec.duration = r.duration;
    std::vector<double> sq[kMethods];
    if (k == 0) {
      rec.path_x.assign(kMethods + 1, {});
      rec.path_y.assign(kMethods + 1, {});
    }
    std::size_t next_scan = 0;
    while (next_scan < scans.size() && scans[next_scan].scan.timestamp <= enc.front().t) ++next_scan;
    for (std::size_t i = 1; i < enc.size(); ++i) {
      const WheelDisplacement u =
          displacement_from_ticks(model, enc[i].left - enc[i - 1].left, enc[i].right - enc[i - 1].right);
      odo = odometry_step(odo, u, model.wheelbase);
      ekf_eap.predict(u);
      ekf_sm.predict(u);
      line_kf.predict(u);
      while (next_scan < scans.size() && scans[next_scan].scan.timestamp <= enc[i].t) {
        const Scan& scan = scans[next_scan++].scan;
        const auto up = ekf_eap.correct(scan, r.world, eap);
        if (up.kind == pose_correction::TrackerUpdateKind::kFull) ++rec.full_updates;
        if (up.kind == pose_correction::TrackerUpdateKind::kHeading) ++rec.heading_updates;
        ekf_sm.correct(scan, r.world, sm);
        std::vector<baselines::localization::LineObservation> obs;
        for (const baselines::laser::ExtractedLine& l : sm.extract_lines(scan).lines) {
          std::vector<Eigen::Vector2d> pts;
          for (const laser::ScanPoint& p : l.points) pts.push_back(p.robot);
          obs.push_back(baselines::localization::line_observation(pts));
        }
        line_kf.update(obs, r.world);
        const Pose2 t = *truth.pose_at(enc[i].t);
        const Pose2 est[kMethods] = {odo, ekf_eap.pose(), ekf_sm.pose(), line_kf.pose()};
        for (int m = 0; m < kMethods; ++m) {
          sq[m].push_back(std::pow(est[m].x - t.x, 2) + std::pow(est[m].y - t.y, 2));
        }
        if (k == 0) {
          for (int m = 0; m <= kMethods; ++m) {
            const Pose2& p = m == 0 ? t : est[m - 1];
            rec.path_x[static_cast<std::size_t>(m)].push_back(p.x);
            rec.path_y[static_cast<std::size_t>(m)].push_back(p.y);
          }
        }
      }
    }
    const auto t_end = truth.pose_at(std::min(enc.back().t, truth.end_time()));
    const Pose2 est[kMethods] = {odo, ekf_eap.pose(), ekf_sm.pose(), line_kf.pose()};
    for (int m = 0; m < kMethods; ++m) {
      rec.final_position_error.push_back(std::hypot(est[m].x - t_end->x, est[m].y - t_end->y));
      rec.final_heading_error.push_back(std::abs(angle_diff(est[m].theta, t_end->theta)));
      rec.rms_position_error.push_back(sq[m].empty() ? 0.0 : std::sqrt(mean(sq[m])));
    }
    return rec;
  }

  reports::ExperimentResults summarise(const Setup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.configuration);
    std::vector<double> fin[kMethods], head[kMethods], rms[kMethods], full, heading;
    Record first;
    for (std::size_t k = 0; k < records.size(); ++k) {
      out.seeds.push_back(plan.run_seed(static_cast<int>(k)));
      const Record r = records[k].get<Record>();
      if (k == 0) first = r;
      for (int m = 0; m < kMethods; ++m) {
        fin[m].push_back(r.final_position_error[static_cast<std::size_t>(m)]);
        head[m].push_back(r.final_heading_error[static_cast<std::size_t>(m)]);
        rms[m].push_back(r.rms_position_error[static_cast<std::size_t>(m)]);
      }
      full.push_back(r.full_updates);
      heading.push_back(r.heading_updates);
    }
    out.datasets.push_back({"sim/" + s.scenario.name, "simulated", text_checksum(sim::to_json(s.scenario).dump()),
                            first.records, first.duration});
    const std::string ds = "sim_" + s.scenario.name;
    for (int m = 0; m < kMethods; ++m) {
      out.results.push_back(
          reports::make_metric(kMethodNames[m], ds, "final_position_error", "m", "monte_carlo_runs", fin[m]));
      out.results.push_back(
          reports::make_metric(kMethodNames[m], ds, "final_heading_error", "rad", "monte_carlo_runs", head[m]));
      out.results.push_back(
          reports::make_metric(kMethodNames[m], ds, "rms_position_error", "m", "monte_carlo_runs", rms[m]));
    }
    reports::Plot plot;
    plot.name = "trajectories_run_0";
    plot.kind = "trajectory";
    plot.title = "Corridor run 0: truth and each estimate at every scan";
    plot.x_label = "x";
    plot.y_label = "y";
    plot.x_unit = plot.y_unit = "m";
    plot.note = "run 0 of " + std::to_string(records.size());
    for (int m = 0; m <= kMethods; ++m) {
      plot.series.push_back({m == 0 ? "truth" : kMethodNames[m - 1], first.path_x[static_cast<std::size_t>(m)],
                             first.path_y[static_cast<std::size_t>(m)]});
    }
    out.plots.push_back(std::move(plot));

    reports::PublishedComparison t;
    t.source = "thesis Table 6.5";
    t.quantity = "E_error (6.43) of the chapter-6 EKF per run";
    t.unit = "mm";
    std::vector<double> ours_mm;
    for (const double e : fin[kEkfEap]) ours_mm.push_back(to_mm(e));
    t.rows = reports::numbered_rows("run", kTable65, ours_mm);
    double pub = 0.0;
    for (double x : kTable65) pub += x / 10.0;
    t.rows.push_back({"mean", pub, to_mm(mean(fin[kEkfEap]))});
    t.claim = "the chapter-6 EKF with EAP matches tracks the 10 m corridor to about 63 mm (E_error)";
    reports::compare_means_only(t, std::vector<double>(std::begin(kTable65), std::end(kTable65)));
    t.note =
        "Runs are not paired with the thesis's. The thesis steered the robot along the "
        "corridor with the EKF's estimate; ours drives open-loop with the odometry's belief. "
        "In a corridor the walls fix heading and lateral position only; along-track position "
        "comes from the end wall once it is within the laser's 8 m (first ~2 m heading-only "
        "updates).";
    out.published.push_back(std::move(t));
    out.notes.push_back(
        fmt::format("Final position error (mean over {} runs): odometry {:.0f} mm, ekf_eap {:.1f} mm, "
                    "ekf_split_and_merge {:.1f} mm, kalman_line_features {:.1f} mm. ekf_eap made {:.0f} full "
                    "and {:.0f} heading-only updates per run.",
                    records.size(), to_mm(mean(fin[kOdometry])), to_mm(mean(fin[kEkfEap])),
                    to_mm(mean(fin[kEkfSplitMerge])), to_mm(mean(fin[kLineKalman])), mean(full), mean(heading)));
    return out;
  }
};

const Registration<LaserTracking> laser_tracking_table_6_5_registration(kInfo);

}  // namespace locbench::experiments::laser_tracking_table_6_5
