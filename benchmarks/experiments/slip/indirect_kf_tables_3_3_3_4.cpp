// Experiment slip/indirect_kf_tables_3_3_3_4: the indirect Kalman filter of §3.5 (eq. 3.18–3.26)
// on simulated Trilobot corridor runs (Monte-Carlo, preset "corridor", whose true wheels are
// the thesis's IKF refinement D' = D(1 + S̄), so the true S_L = 0.003607, S_R = 0.003591,
// δB = 0). Per run: slip-corrected wheel travel from the second EKF's detector, the IKF with the
// compass heading as reference (the thesis), and the same with one measured end position
// (ours). The estimates are averaged over runs (Table 3.3), the nominal model corrected with
// D' = D(1 + S̄), B' = B + δB̄, and the second EKF re-run on the same logs (Table 3.4).
// What the runs can determine is taken from the stacked measurement Jacobian of the IKF.
#include <fmt/format.h>

#include <array>
#include <cmath>

#include "algorithms/slip/indirect_kalman_filter.h"
#include "algorithms/slip/slip_compass_ekf.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/statistics.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"
#include "pipelines/scenario_option.h"
#include "pipelines/slip_sim.h"
#include "reports/findings.h"

namespace locbench::experiments::slip_indirect_kf_tables_3_3_3_4 {
using locbench::calibration::IdentifiabilityReport, locbench::calibration::ParameterFinding;
using locbench::slip::HeadingSource, locbench::slip::ikf_identifiability, locbench::slip::IkfRunResult,
    locbench::slip::IkfSample, locbench::slip::IndirectKfOptions, locbench::slip::run_indirect_kf,
    locbench::slip::run_slip_ekf, locbench::slip::SlipDetectorOptions, locbench::slip::SlipEkfOptions,
    locbench::slip::SlipEkfRun, locbench::slip::SlipEkfStep, locbench::slip::SlipModel;

const ExperimentInfo kInfo{
    .name = "slip/indirect_kf_tables_3_3_3_4",
    .description =
        "Indirect Kalman filter for S_L, S_R, δB on simulated straight corridor runs "
        "(Tables 3.3/3.4): estimates, identifiability, error after correcting the diameters",
    .reading = {"Finding (ours): with 12.64 mm ticks the per-sample odometry heading swings by ±1 tick "
                "(±3.7°) while the true heading does not; Z = compass − odometry contains that swing, and "
                "the δB regressor Σ(U_L − U_R)/B² is exactly −θ_odometry/B (the S_R + S_L regressor is "
                "θ_odometry/2), so the heading-only IKF fits the quantization swing with a large δB and a "
                "negative common scale. Its 'corrected' model is worse than the nominal one; the "
                "end-position variant holds δB at 0 and is not affected.",
                "The δθ row of F uses the nominal B and the odometry heading; the transition is the 6×6 "
                "of eq. 3.20–3.23 (the printed eq. 3.25 repeats the S_L row). Measurement sign: "
                "Z = compass heading − odometry heading, which with D' = D(1 + S) makes S > 0 for a wheel "
                "larger than nominal (see algorithms/slip/indirect_kalman_filter.h)."}};

constexpr double kPublishedImprovement[10] = {16.34, 43.15, 24.80, 16.74, 46.67, 25.55, 22.51, 65.75, 53.27, 21.12};
constexpr int kVariants = 2;
const char* const kVariantNames[kVariants] = {"ikf_heading_only", "ikf_heading_end_position"};
const char* const kParamNames[3] = {"S_R", "S_L", "dB"};

// The commanded path as IKF samples (no noise): straight legs of `leg` metres at `step` metres
// per sample, and (if turns > 0) on-the-spot 90° left turns between them at `turn_step` rad per
// sample. The reference heading is measured at every sample.
std::vector<IkfSample> ideal_path(double leg, int legs, double step, double turn_step, double b) {
  std::vector<IkfSample> out;
  for (int l = 0; l < legs; ++l) {
    const int n = static_cast<int>(std::round(leg / step));
    for (int i = 0; i < n; ++i) out.push_back({{step, step}, 0.0});
    if (l + 1 < legs) {
      const int m = static_cast<int>(std::round((kPi / 2.0) / turn_step));
      const double w = turn_step * b / 2.0;
      for (int i = 0; i < m; ++i) out.push_back({{-w, w}, 0.0});
    }
  }
  return out;
}

std::string describe(const IdentifiabilityReport& r) {
  std::string s = fmt::format("rank {} of {}", r.rank, r.parameter_count);
  for (const auto& c : r.undetermined_combinations) s += "; undetermined: " + c;
  return s;
}

struct Options {
  int runs = 10;
  int calibration_runs = 4;
  sim::Scenario scenario = sim::preset("corridor");
  SlipDetectorOptions detector;
  IndirectKfOptions ikf;
  double end_position_sigma_mm = 5.0;
  // The thesis feeds the IKF the slip-corrected travel (note to eq. 3.25). On this preset the
  // detector's false alarms break the telescoping of the quantization errors (see the notes), so
  // the default is the raw encoder travel.
  bool slip_corrected_travel = false;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.field("calibration_runs", o.calibration_runs, "", at_least(1), "runs the slip model is calibrated on");
  v.coded("scenario", o.scenario, scenario_json, scenario_option, "the simulated corridor run (datasets/sim)");
  v.nested("detector", o.detector, "the slip detector (slip_detector.h)");
  v.nested("ikf", o.ikf, "the indirect Kalman filter (indirect_kalman_filter.h)");
  v.field("end_position_sigma_mm", o.end_position_sigma_mm, "mm", positive(), "σ of each run's measured end position");
  v.flag("slip_corrected_travel", o.slip_corrected_travel, "feed the IKF the slip-corrected travel");
}

// The options and what is computed once from them.
struct IkfSetup : Options {
  explicit IkfSetup(const Options& o) : Options(o) {}
  SlipEkfOptions ekf_opt;
  double end_var = 0.0;  // [m²] variance of the measured end position
  SlipModel model;       // μ, σ of Δθ' from the calibration runs
  nlohmann::json configuration;
};

// The IKF's estimates over the runs: [variant][S_R, S_L, δB], one value per run.
using Estimates = std::array<std::array<std::vector<double>, 3>, kVariants>;

Estimates estimates_of(const std::vector<nlohmann::json>& records, int runs) {
  Estimates est;
  for (int k = 0; k < runs; ++k) {
    const nlohmann::json& rec = records[static_cast<std::size_t>(k)];
    for (int v = 0; v < kVariants; ++v) {
      for (int p = 0; p < 3; ++p) {
        est[static_cast<std::size_t>(v)][static_cast<std::size_t>(p)].push_back(
            rec.at("estimates").at(v).at(p).get<double>());
      }
    }
  }
  return est;
}

// The true S_R, S_L and δB relative to the nominal model (D_true = D_nominal (1 + S)).
std::array<double, 3> true_values(const RobotParams& robot) {
  return {robot.actual.diameter_right / robot.nominal.diameter_right - 1.0,
          robot.actual.diameter_left / robot.nominal.diameter_left - 1.0,
          robot.actual.wheelbase - robot.nominal.wheelbase};
}

// The second EKF's models (Table 3.4): the nominal one, corrected with each variant's mean
// estimates (D' = D(1 + S̄), B' = B + δB̄), and the true geometry.
constexpr int kModels = 4;
const char* const kModelNames[kModels] = {"ekf_nominal_model", "ekf_ikf_heading_only_model",
                                          "ekf_ikf_heading_end_position_model", "ekf_true_geometry"};

std::array<NominalModel, kModels> ekf_models(const RobotParams& robot, const Estimates& est) {
  const NominalModel nominal = robot.nominal_model();
  const auto corrected = [&](std::size_t v) {
    NominalModel m = nominal;
    m.meters_per_tick_right *= 1.0 + mean(est[v][0]);
    m.meters_per_tick_left *= 1.0 + mean(est[v][1]);
    m.wheelbase += mean(est[v][2]);
    return m;
  };
  return {nominal, corrected(0), corrected(1), robot.actual_model()};
}

// Per model, the final position error of each run and its reduction against the nominal model [%].
struct ModelErrors {
  std::array<std::vector<double>, kModels> error, improvement;
};

// The second pass: the slip-corrected EKF re-run under each model on every run's logged ticks
// (the records carry them: the models need every run's estimates, and the runs are not simulated
// again), in parallel, each run writing only its own slot.
ModelErrors rerun_under_models(const IkfSetup& u, const McPlan& plan, const std::vector<nlohmann::json>& records,
                               const std::array<NominalModel, kModels>& models) {
  std::vector<std::array<double, kModels>> per_run(static_cast<std::size_t>(plan.runs));
  parallel_tasks(plan.threads, per_run.size(), [&](std::size_t k) {
    const slip_sim::RunTicks ticks = slip_sim::run_ticks_from_json(records[k].at("run"));
    for (std::size_t m = 0; m < kModels; ++m) {
      const slip_sim::RunData d = slip_sim::run_data(ticks, models[m]);
      const SlipEkfRun r =
          run_slip_ekf(d.samples, d.initial_compass, u.model, {}, u.ekf_opt, models[m].wheelbase, d.truth.front());
      per_run[k][m] = slip_sim::final_position_error(r, d);
    }
  });
  ModelErrors out;
  for (const auto& e : per_run) {
    for (std::size_t m = 0; m < kModels; ++m) {
      out.error[m].push_back(e[m]);
      out.improvement[m].push_back(100.0 * (1.0 - out.error[m].back() / out.error[0].back()));
    }
  }
  return out;
}

// What the commanded paths determine (exact null directions), per variant: a straight run and an
// L-shaped path (2 m, 90° left, 2 m, open).
struct PathIdentifiability {
  std::array<IdentifiabilityReport, kVariants> straight, square;
};

PathIdentifiability path_identifiability(const IkfSetup& u, double b, const std::array<double, 3>& truth) {
  const sim::Scenario& scenario = u.scenario;
  const double step = scenario.drive.speed / scenario.encoders.timing.rate;
  const double turn_step = scenario.drive.turn_rate / scenario.encoders.timing.rate;
  const Eigen::Vector3d at_truth(truth[0], truth[1], truth[2]);
  const auto straight = ideal_path(scenario.motion.distance, 1, step, turn_step, b);
  const auto square = ideal_path(2.0, 2, step, turn_step, b);
  const double heading_variance = u.ikf.heading_variance;
  return {{ikf_identifiability(straight, 0.0, b, heading_variance, at_truth, {}, 1e-10),
           ikf_identifiability(straight, 0.0, b, heading_variance, at_truth, u.end_var, 1e-10)},
          {ikf_identifiability(square, 0.0, b, heading_variance, at_truth, {}, 1e-10),
           ikf_identifiability(square, 0.0, b, heading_variance, at_truth, u.end_var, 1e-10)}};
}

// Each variant's estimates over the runs, with the straight path's identifiability.
std::vector<reports::MetricResult> estimate_metrics(const std::string& ds, const Estimates& est,
                                                    const PathIdentifiability& id, const std::array<double, 3>& truth) {
  const char* remedy[3] = {
      "a straight run's headings fix only S_R − S_L; the common scale needs a distance "
      "reference (a measured end position, as ikf_heading_end_position)",
      "a straight run's headings fix only S_R − S_L; the common scale needs a distance "
      "reference (a measured end position, as ikf_heading_end_position)",
      "δB only acts through U_R − U_L, which is ~0 on a straight run; it needs turns (or "
      "curves) AND a distance reference: headings alone never separate δB from the common "
      "diameter scale (scaling D_L, D_R, B together leaves every heading unchanged)"};
  std::vector<reports::MetricResult> out;
  for (std::size_t v = 0; v < kVariants; ++v) {
    for (std::size_t p = 0; p < 3; ++p) {
      reports::MetricResult m =
          reports::make_metric(kVariantNames[v], ds, kParamNames[p], p == 2 ? "m" : "", "monte_carlo_runs", est[v][p]);
      m.better = "stable";  // estimates: any change is a change of method
      const ParameterFinding& f = id.straight[v].parameters[p];
      m.identifiable = f.identifiable;
      if (!f.identifiable) {
        m.note = f.reason + "; " + remedy[p];
      } else {
        m.note = fmt::format("true value {:.6g}", truth[p]);
      }
      out.push_back(std::move(m));
    }
  }
  return out;
}

// Each model's final position error, and its reduction against the nominal model.
std::vector<reports::MetricResult> error_metrics(const std::string& ds, const ModelErrors& errors) {
  std::vector<reports::MetricResult> out;
  for (std::size_t m = 0; m < kModels; ++m) {
    out.push_back(
        reports::make_metric(kModelNames[m], ds, "final_position_error", "m", "monte_carlo_runs", errors.error[m]));
    if (m > 0) {
      reports::MetricResult r =
          reports::make_metric(kModelNames[m], ds, "error_reduction", "%", "monte_carlo_runs", errors.improvement[m]);
      r.better = "higher";
      out.push_back(std::move(r));
    }
  }
  return out;
}

// Table 3.3: the mean IKF estimates.
reports::PublishedComparison table_3_3(const Estimates& est, const std::array<double, 3>& truth,
                                       const PathIdentifiability& id, double end_position_sigma_mm) {
  reports::PublishedComparison t33;
  t33.source = "thesis Table 3.3";
  t33.quantity = "mean IKF estimates over the runs (δB in mm, as the thesis: B' = 197.929964 mm)";
  t33.unit = "1 / mm";
  t33.rows = {{"S_L (heading only)", 0.003607, mean(est[0][1])},
              {"S_R (heading only)", 0.003591, mean(est[0][0])},
              {"dB [mm] (heading only)", -0.000036, to_mm(mean(est[0][2]))},
              {"S_L (heading + end position)", std::nullopt, mean(est[1][1])},
              {"S_R (heading + end position)", std::nullopt, mean(est[1][0])},
              {"dB [mm] (heading + end position)", std::nullopt, to_mm(mean(est[1][2]))},
              {"true S_L", 0.003607, truth[1]},
              {"true S_R", 0.003591, truth[0]},
              {"true dB [mm]", std::nullopt, to_mm(truth[2])}};
  t33.note = fmt::format(
      "The simulated robot's true wheels are the thesis's refined ones, so the true S equal the "
      "published means. With the compass heading as the only reference the IKF can determine "
      "S_R − S_L alone (true {:.2e}; straight path: {}), so its S_L, S_R stay near the prior "
      "(0) plus half the difference, and δB stays at its prior. One measured end position "
      "(σ = {} mm) adds the common scale ({}); δB stays undetermined on straight runs. The "
      "thesis's equal S_L ≈ S_R ≈ 0.0036 cannot come from headings on straight runs; how its "
      "filter reached them is not recoverable from the text. Its δB = −0.000036 is in mm "
      "(B' = 197.929964 mm), i.e. no correction.",
      truth[0] - truth[1], describe(id.straight[0]), end_position_sigma_mm, describe(id.straight[1]));
  t33.claim = "the IKF estimates S_L ≈ S_R ≈ 0.0036 and δB ≈ 0 from the compass heading on straight runs";
  t33.tolerance = 0.0005;
  t33.tolerance_basis = "0.0005 (1/mm, or mm for δB): a seventh of the true S, well above the runs' scatter";
  return t33;
}

// Table 3.4: the per-run error reduction after correcting D_L, D_R, B.
reports::PublishedComparison table_3_4(const ModelErrors& errors) {
  const auto& improvement = errors.improvement;
  reports::PublishedComparison t34;
  t34.source = "thesis Table 3.4";
  t34.quantity = "final-error reduction of the slip-corrected EKF after correcting D_L, D_R, B";
  t34.unit = "%";
  for (std::size_t i = 0; i < 10; ++i) {
    reports::PublishedRow row{fmt::format("run {} (heading + end position)", i + 1), kPublishedImprovement[i],
                              std::nullopt};
    if (i < improvement[2].size()) row.ours = improvement[2][i];
    t34.rows.push_back(row);
  }
  double pub_mean = 0.0;
  for (double x : kPublishedImprovement) pub_mean += x / 10.0;
  t34.rows.push_back({"mean (heading + end position)", pub_mean, mean(improvement[2])});
  t34.rows.push_back({"mean (heading only)", pub_mean, mean(improvement[1])});
  t34.rows.push_back({"mean (true geometry, oracle)", std::nullopt, mean(improvement[3])});
  t34.claim = "correcting D_L, D_R, B with the IKF's estimates cuts the final error by 34% on average";
  reports::compare_means_only(t34,
                              std::vector<double>(std::begin(kPublishedImprovement), std::end(kPublishedImprovement)));
  t34.note =
      "Same logs re-processed with the corrected model (common random numbers); runs are not "
      "paired with the thesis's. Heading-only estimates barely change the diameters, so they "
      "cannot reproduce the 16–66% reduction; the end-position variant recovers the common "
      "scale (the ~0.36% along-track error, ≈ 36 mm over 10 m) and shows the kind of "
      "reduction the thesis reports.";
  return t34;
}

std::string identifiability_note(double distance, const PathIdentifiability& id) {
  return fmt::format(
      "Identifiability of [S_R, S_L, δB] from the IKF's stacked measurement Jacobian "
      "(analyze_identifiability), commanded paths: straight {} m, headings only: {}; straight + "
      "end position: {}; L-shaped path (2 m, 90° turn, 2 m), headings only: {}; L + end position: "
      "{}. So straight runs determine S_R − S_L (and, with a distance reference, S_L and S_R) "
      "but never δB; a path with turns plus a distance reference determines all three.",
      distance, describe(id.straight[0]), describe(id.straight[1]), describe(id.square[0]), describe(id.square[1]));
}

std::string travel_note(bool slip_corrected_travel) {
  return fmt::format(
      "IKF input: {}. With 12.64 mm ticks a sample's θ_E swings by one tick (3.7°) and the next "
      "sample swings back (the counts are cumulative, so the errors telescope). The slip rule "
      "picks exactly the extreme swings (at 95% about 5% of slip-free samples, and on this "
      "preset most detections are such false alarms) and replaces θ_E by θ_C, leaving the "
      "returning swing uncorrected: the 'corrected' dead reckoning drifts by metres over 10 m. "
      "Harmless inside the compass EKF (the compass heading is absolute), fatal for the IKF's "
      "odometry heading; set slip_corrected_travel = true to see it.",
      slip_corrected_travel ? "slip-corrected travel (as the thesis)" : "raw encoder travel (default)");
}

class SlipIndirectKf final : public MonteCarloExperiment<Options, IkfSetup> {
 public:
  IkfSetup setup(const Options& o, const McPlan& plan) const override {
    IkfSetup u(o);
    u.ekf_opt.detector = o.detector;
    u.end_var = std::pow(mm(o.end_position_sigma_mm), 2);
    u.configuration = recorded(o, plan);
    u.model = slip_sim::calibrate(u.scenario, plan.seed, o.calibration_runs, {}).compass;
    return u;
  }

  // Run k: the IKF's estimates [variant][S_R, S_L, δB] from the slip-corrected EKF's log.
  nlohmann::json run_task(const IkfSetup& u, const McPlan& plan, int k) const override {
    const NominalModel nominal = u.scenario.robot.params().nominal_model();
    const double b = nominal.wheelbase;
    const sim::SimulationResult sim = slip_sim::simulate(u.scenario, plan.run_seed(k));
    const slip_sim::RunTicks ticks = slip_sim::run_ticks(sim);
    const slip_sim::RunData d = slip_sim::run_data(ticks, nominal);
    const SlipEkfRun ekf = run_slip_ekf(d.samples, d.initial_compass, u.model, {}, u.ekf_opt, b, d.truth.front());
    // IKF input: slip-corrected travel (eq. 3.25 note), compass heading where trusted.
    std::vector<IkfSample> s;
    Pose2 odo = d.truth.front();
    for (std::size_t i = 0; i < d.samples.size(); ++i) {
      const SlipEkfStep& st = ekf.steps[i];
      IkfSample x{u.slip_corrected_travel ? st.decision.wheels : d.samples[i].u, {}};
      if (st.source == HeadingSource::kCompass) x.reference_heading = d.samples[i].compass;
      s.push_back(x);
      odo = odometry_step(odo, x.u, b);
    }
    const Eigen::Vector2d end_err(d.truth.back().x - odo.x, d.truth.back().y - odo.y);
    // Ours: δB, undetermined on straight runs, is held at 0 (prior variance 0) when the end
    // position is used; the thesis's variant estimates all three.
    IndirectKfOptions frozen = u.ikf;
    frozen.initial_covariance(5) = 0.0;
    const IkfRunResult r[kVariants] = {run_indirect_kf(s, d.truth.front().theta, u.ikf, b),
                                       run_indirect_kf(s, d.truth.front().theta, frozen, b, end_err, u.end_var)};
    // The run itself, for the second pass under the corrected models (summarise).
    nlohmann::json rec = {
        {"records", sim.log.record_count()}, {"duration", sim.duration}, {"run", slip_sim::run_ticks_json(ticks)}};
    for (int v = 0; v < kVariants; ++v) {
      rec["estimates"].push_back({r[v].s_right, r[v].s_left, r[v].delta_b});
    }
    return rec;
  }

  reports::ExperimentResults summarise(const IkfSetup& u, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(u.configuration);
    const sim::Scenario& scenario = u.scenario;
    const RobotParams robot = scenario.robot.params();
    const std::array<double, 3> truth = true_values(robot);
    const Estimates est = estimates_of(records, plan.runs);
    for (int k = 0; k < plan.runs; ++k) out.seeds.push_back(plan.run_seed(k));
    const ModelErrors errors = rerun_under_models(u, plan, records, ekf_models(robot, est));
    const PathIdentifiability id = path_identifiability(u, robot.nominal_model().wheelbase, truth);

    out.configuration["scenario"] = sim::to_json(scenario);
    out.datasets.push_back({"sim/" + scenario.name, "simulated", text_checksum(out.configuration["scenario"].dump()),
                            records.front().at("records").get<std::size_t>(),
                            records.front().at("duration").get<double>()});
    const std::string ds = "sim_" + scenario.name;
    for (auto& m : estimate_metrics(ds, est, id, truth)) out.results.push_back(std::move(m));
    for (auto& m : error_metrics(ds, errors)) out.results.push_back(std::move(m));
    out.published.push_back(table_3_3(est, truth, id, u.end_position_sigma_mm));
    out.published.push_back(table_3_4(errors));
    out.notes.push_back(identifiability_note(scenario.motion.distance, id));
    out.notes.push_back(travel_note(u.slip_corrected_travel));
    return out;
  }
};

const Registration<SlipIndirectKf> slip_indirect_kf_tables_3_3_3_4_registration(kInfo);

}  // namespace locbench::experiments::slip_indirect_kf_tables_3_3_3_4
