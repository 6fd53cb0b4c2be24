#include "pipelines/calibration_umbmark.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "algorithms/calibration/umbmark_design_model.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/statistics.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"
#include "datasets/sim/umbmark_input.h"
#include "reports/published_rows.h"

namespace locbench::experiments {
using locbench::baselines::calibration::classic_umbmark, locbench::baselines::calibration::ClassicUmbmarkResult;
using locbench::calibration::analyze_umbmark_design, locbench::calibration::error_params,
    locbench::calibration::IdentifiabilityReport, locbench::calibration::improved_umbmark,
    locbench::calibration::ImprovedUmbmarkResult, locbench::calibration::ParameterFinding,
    locbench::calibration::UmbmarkDesign, locbench::calibration::UmbmarkDesignFinding,
    locbench::calibration::UmbmarkErrorParams, locbench::calibration::UmbmarkIdentifiabilityOptions,
    locbench::calibration::UmbmarkParameterSet;
namespace {

constexpr int kMethods = 3;
const char* const kMethodNames[kMethods] = {"uncalibrated", "umbmark_classic", "umbmark_improved"};

UmbmarkAngleFormula angle_formula(const std::string& s) {
  if (s == "x") return UmbmarkAngleFormula::kX;
  if (s == "y") return UmbmarkAngleFormula::kY;
  if (s == "mean") return UmbmarkAngleFormula::kMean;
  throw UsageError("calibration: angle_formula must be \"x\", \"y\" or \"mean\", not \"" + s + "\"");
}

// Final pose error of dead reckoning (with the robot's nominal model) on a simulated run.
std::pair<double, double> final_dead_reckoning_error(const sim::SimulationResult& r) {
  const Pose2 e = sim::dead_reckoning_end_error(r);
  return {std::hypot(e.x, e.y), std::abs(e.theta)};
}

struct Samples {
  std::vector<double> e_max_after[kMethods];
  std::vector<double> validation_position[kMethods];
  std::vector<double> validation_heading[kMethods];
  std::vector<double> E_d_error[kMethods];
  std::vector<double> E_b_error[kMethods];
  std::vector<double> E_o_error[kMethods];
  std::vector<double> run_sigma;
};

// One Monte-Carlo experiment: per method (uncalibrated, classic, improved) E_max,syst after
// re-running the square, validation-path errors and E_d, E_b, E_o errors against the truth.
struct UmbmarkRecord {
  std::array<double, kMethods> e_max_after{};
  std::array<double, kMethods> validation_position{};
  std::array<double, kMethods> validation_heading{};
  std::array<std::array<double, 3>, kMethods> parameter_error{};
  double run_sigma = 0.0;
  std::size_t records = 0;
  double duration = 0.0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(UmbmarkRecord, e_max_after, validation_position, validation_heading, parameter_error,
                                   run_sigma, records, duration)

// Parameter errors against the truth, each flagged with what the square can identify.
void add_parameter_results(reports::ExperimentResults& out, const std::string& dataset, const sim::Scenario& scenario,
                           const Samples& s) {
  // The Fisher analysis is taken at the nominal robot (E = 1), where the methods linearise and
  // the square's null direction is exact; with the runs' own scatter as measurement noise.
  const UmbmarkErrorParams at_nominal{};
  UmbmarkIdentifiabilityOptions idopt;
  idopt.run_sigma = mean(s.run_sigma);
  idopt.runs_per_direction = scenario.motion.runs;
  const UmbmarkDesignFinding findings[kMethods] = {
      {},
      analyze_umbmark_design(UmbmarkDesign::kSquare, UmbmarkParameterSet::kClassic, scenario.robot.nominal,
                             scenario.robot.encoder, scenario.motion.side, at_nominal, idopt),
      analyze_umbmark_design(UmbmarkDesign::kSquareWithLegTicks, UmbmarkParameterSet::kImproved, scenario.robot.nominal,
                             scenario.robot.encoder, scenario.motion.side, at_nominal, idopt)};
  const char* names[3] = {"E_d", "E_b", "E_o"};
  for (int m = 1; m < kMethods; ++m) {
    const std::vector<double>* errs[3] = {&s.E_d_error[m], &s.E_b_error[m], &s.E_o_error[m]};
    for (int p = 0; p < 3; ++p) {
      reports::MetricResult r = reports::make_metric(kMethodNames[m], dataset, std::string(names[p]) + "_error", "",
                                                     "monte_carlo_runs", *errs[p]);
      r.better = "closer_to_zero";
      if (m == 1 && p == 2) {
        r.note = "input, not estimated: classic UMBmark takes E_s from a tape measurement";
      }
      for (const ParameterFinding& f : findings[m].report.parameters) {
        if (f.name != names[p]) continue;
        r.identifiable = f.identifiable;
        if (!f.identifiable) {
          r.note = f.reason;
          for (const auto& [param, remedy] : findings[m].remedies) {
            if (param == f.name) r.note += "; to determine it: " + remedy;
          }
        }
      }
      out.results.push_back(std::move(r));
    }
    const IdentifiabilityReport& rep = findings[m].report;
    out.notes.push_back(
        fmt::format("{} — design: {}; parameters: {}. Fisher information rank {} of {}, condition number "
                    "{:.3g}, per-run σ {:.3f} m (from the runs' scatter).",
                    kMethodNames[m], to_string(findings[m].design), to_string(findings[m].parameter_set), rep.rank,
                    rep.parameter_count, rep.condition_number, idopt.run_sigma));
  }
}

// Table 2.1 (Trilobot, 1.6 m square, E_max,syst in mm: before / UMBmark / improved).
void add_table_2_1(reports::ExperimentResults& out, const std::vector<std::array<double, 3>>& rows) {
  const double published[5][3] = {{670, 158, 117}, {722, 185, 141}, {650, 151, 109}, {773, 221, 179}, {748, 202, 159}};
  const char* columns[3] = {"before", "UMBmark", "improved"};
  for (int c = 0; c < 3; ++c) {
    std::vector<double> ours_mm;
    for (const auto& r : rows) ours_mm.push_back(r[c] * 1e3);
    out.published.push_back(reports::numbered_comparison("thesis Table 2.1", std::string("E_max,syst ") + columns[c],
                                                         "mm", "experiment", reports::table_column(published, c),
                                                         ours_mm));
  }
  // Plain words from the numbers.
  double pub[3] = {0, 0, 0}, ours[3] = {0, 0, 0};
  for (int i = 0; i < 5; ++i) {
    for (int c = 0; c < 3; ++c) pub[c] += published[i][c] / 5.0;
  }
  for (const auto& r : rows) {
    for (int c = 0; c < 3; ++c) ours[c] += r[c] * 1e3 / static_cast<double>(rows.size());
  }
  const std::string note = fmt::format(
      "Published means: {:.0f} mm before, {:.0f} mm after UMBmark ({:.1f}× better), {:.0f} mm "
      "after the improved method ({:.1f}×). Simulated means over {} runs: {:.0f} mm before, "
      "{:.0f} mm after classic ({:.1f}×), {:.0f} mm after improved ({:.1f}×). {} The "
      "simulator has the thesis's blamed effects (turn slip, whole-tick commands of a 22-count "
      "encoder) but its true robot is an assumption (Table 3.3 diameters), so only the size of "
      "the gains, not each row, is comparable. The improved method's E_o is fixed by the "
      "commanded leg counts, not measured (see the E_o_error note); with E_s measured and "
      "compensated before the runs (Borenstein's protocol, as here) the two methods differ only "
      "by the rounding of the leg counts. Applying a tape E_s to runs that were not "
      "E_s-compensated puts the E_s error on the turns twice and makes classic look worse — a "
      "plausible reason for the thesis's gap.",
      pub[0], pub[1], pub[0] / pub[1], pub[2], pub[0] / pub[2], rows.size(), ours[0], ours[1], ours[0] / ours[1],
      ours[2], ours[0] / ours[2],
      ours[2] < ours[1] ? "As in the thesis, improved ends below classic."
                        : "Unlike the thesis, improved does not end below classic here.");
  for (auto& t : out.published) t.note = note;
  out.notes.push_back(note);
}

}  // namespace

UmbmarkOptions umbmark_defaults(const std::string& preset) {
  UmbmarkOptions o;
  o.scenario = sim::preset(preset);
  o.effects.wheels_driven_independently = !o.scenario.drive.equal_wheel_ticks;
  o.validation_waypoints = irregular_validation_path(o.scenario.motion.side);
  return o;
}

std::vector<Eigen::Vector2d> irregular_validation_path(double side) {
  const double L = side;
  return {{L, 0.0}, {L, 0.6 * L}, {0.3 * L, 0.9 * L}, {-0.2 * L, 0.3 * L}, {0.0, 0.0}};
}

CalibrationUmbmark::CalibrationUmbmark(std::string preset)
    : MonteCarloExperiment({.name = "calibration/" + preset,
                            .description = "UMBmark on the simulated " + preset +
                                           " robot: classic vs improved calibration, E_max,syst "
                                           "before/after, parameter errors, validation-path error, "
                                           "identifiability (Monte-Carlo)"}),
      preset_(std::move(preset)) {}

UmbmarkSetup CalibrationUmbmark::setup(const UmbmarkOptions& o, const McPlan& plan) const {
  UmbmarkSetup u;
  sim::Scenario& scenario = u.scenario;
  scenario = o.scenario;
  if (scenario.motion.kind != sim::MotionKind::kUmbmark) {
    throw UsageError(name() + ": the scenario's motion must be the UMBmark square");
  }
  if (!o.effects.turn_slip) scenario.slip.turn.rate = 0.0;
  scenario.drive.equal_wheel_ticks = !o.effects.wheels_driven_independently;
  // Borenstein's protocol: E_s = D_a/D_n is measured with a tape and compensated *before*
  // the runs (the nominal diameters are scaled by it), so the square's return errors carry
  // no E_s turn error and the calibration takes E_s = 1 relative to that nominal model. An
  // inaccurate tape leaves a relative error on it.
  if (o.effects.tape_measure) {
    const double e_s =
        error_params(scenario.robot.nominal, scenario.robot.actual).E_o * (1.0 + o.effects.tape_measure_relative_error);
    scenario.robot.nominal.diameter_left *= e_s;
    scenario.robot.nominal.diameter_right *= e_s;
  }
  u.classic.angles = u.improved.angles = angle_formula(o.angle_formula);
  u.validation = o.validation_waypoints;
  u.configuration = recorded(o, plan);
  u.configuration["scenario"] = sim::to_json(scenario);
  return u;
}

nlohmann::json CalibrationUmbmark::run_task(const UmbmarkSetup& u, const McPlan& plan, int k) const {
  const sim::Scenario& scenario = u.scenario;
  const std::uint64_t seed = plan.run_seed(k);
  const sim::SimulationResult before = sim::simulate(scenario, seed);
  const UmbmarkErrorParams truth = error_params(scenario.robot.nominal, scenario.robot.actual);
  const UmbmarkInput input = sim::umbmark_input(scenario, before.umbmark_runs, 1.0);
  const ClassicUmbmarkResult classic = classic_umbmark(input, u.classic);
  const ImprovedUmbmarkResult improved = improved_umbmark(input, u.improved);
  UmbmarkRecord r;
  r.run_sigma = classic.centroids.run_sigma;
  r.records = before.log.record_count();
  r.duration = before.duration;
  const WheelGeometry corrected[kMethods] = {scenario.robot.nominal, classic.corrected, improved.corrected};
  const double estimates[kMethods][3] = {
      {1.0, 1.0, 1.0}, {classic.E_d, classic.E_b, classic.E_s}, {improved.E_d, improved.E_b, improved.E_o}};
  for (int m = 0; m < kMethods; ++m) {
    sim::Scenario again = scenario;
    again.robot.nominal = corrected[m];
    const sim::SimulationResult after = sim::simulate(again, Rng::derive_seed(seed, 1));
    r.e_max_after[m] = sim::summarize_umbmark(after.umbmark_runs).e_max_syst;
    sim::Scenario check = again;
    check.motion.kind = sim::MotionKind::kWaypoints;
    check.motion.waypoints = u.validation;
    const auto [pos, head] = final_dead_reckoning_error(sim::simulate(check, Rng::derive_seed(seed, 2)));
    r.validation_position[m] = pos;
    r.validation_heading[m] = head;
    r.parameter_error[m] = {estimates[m][0] - truth.E_d, estimates[m][1] - truth.E_b, estimates[m][2] - truth.E_o};
  }
  return r;
}

reports::ExperimentResults CalibrationUmbmark::summarise(const UmbmarkSetup& u, const McPlan& plan,
                                                         const std::vector<nlohmann::json>& records) const {
  reports::ExperimentResults out = start_results(u.configuration);
  Samples s;
  std::vector<std::array<double, 3>> table_rows;  // E_max,syst before / classic / improved
  for (std::size_t k = 0; k < records.size(); ++k) {
    out.seeds.push_back(plan.run_seed(static_cast<int>(k)));
    const auto r = records[k].get<UmbmarkRecord>();
    s.run_sigma.push_back(r.run_sigma);
    for (int m = 0; m < kMethods; ++m) {
      s.e_max_after[m].push_back(r.e_max_after[m]);
      s.validation_position[m].push_back(r.validation_position[m]);
      s.validation_heading[m].push_back(r.validation_heading[m]);
      if (m > 0) {
        s.E_d_error[m].push_back(r.parameter_error[m][0]);
        s.E_b_error[m].push_back(r.parameter_error[m][1]);
        s.E_o_error[m].push_back(r.parameter_error[m][2]);
      }
    }
    table_rows.push_back(r.e_max_after);
  }
  const auto first = records.front().get<UmbmarkRecord>();
  const std::string dataset = "sim_" + preset_;
  out.datasets.push_back({"sim/" + u.scenario.name, "simulated", text_checksum(out.configuration["scenario"].dump()),
                          first.records, first.duration});
  for (int m = 0; m < kMethods; ++m) {
    const std::string method = kMethodNames[m];
    out.results.push_back(
        reports::make_metric(method, dataset, "e_max_syst", "m", "monte_carlo_runs", s.e_max_after[m]));
    out.results.push_back(reports::make_metric(method, dataset, "validation_final_position_error", "m",
                                               "monte_carlo_runs", s.validation_position[m]));
    out.results.push_back(reports::make_metric(method, dataset, "validation_final_heading_error", "rad",
                                               "monte_carlo_runs", s.validation_heading[m]));
  }
  add_parameter_results(out, dataset, u.scenario, s);
  if (preset_ == "umbmark_trilobot") add_table_2_1(out, table_rows);
  return out;
}

}  // namespace locbench::experiments
