#pragma once
// The UMBmark experiment simulated the way the thesis ran it (§2.1, §2.4), registered once per
// robot: calibration/umbmark_trilobot and calibration/umbmark_borenstein
// (calibration/umbmark_*.cpp). Per Monte-Carlo run: drive the bidirectional square (5 CW + 5 CCW)
// with the uncalibrated robot, calibrate with classic UMBmark (baseline) and the thesis's
// improved method, re-run the square with each corrected nominal model (same noise for all:
// common random numbers), and drive an independent validation path. Reports E_max,syst
// before/after, parameter errors against the simulator's truth, validation pose errors, what the
// square can identify, and Table 2.1 beside our figures (Trilobot only).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "algorithms/calibration/umbmark_improved.h"
#include "baselines/calibration/umbmark_classic.h"
#include "datasets/sim/scenario.h"
#include "experiment_framework/monte_carlo.h"
#include "pipelines/scenario_option.h"

namespace locbench::experiments {

// Which of the thesis's protocol effects are on (§2.1, §2.4).
struct UmbmarkEffects {
  bool turn_slip = true;
  bool tape_measure = true;  // E_s measured with a tape and compensated before the runs
  double tape_measure_relative_error = 0.0;
  bool wheels_driven_independently = false;
};

struct UmbmarkOptions {
  int runs = 10;
  sim::Scenario scenario;
  std::string angle_formula = "x";
  UmbmarkEffects effects;
  std::vector<Eigen::Vector2d> validation_waypoints;  // [m]
};
template <class V>
void visit_fields(V& v, UmbmarkEffects& e) {
  v.flag("turn_slip", e.turn_slip, "the simulator's slip in turns");
  v.flag("tape_measure", e.tape_measure, "E_s measured with a tape and compensated before the runs");
  v.field("tape_measure_relative_error", e.tape_measure_relative_error, "", any_finite(),
          "relative error of that tape measurement");
  v.flag("wheels_driven_independently", e.wheels_driven_independently, "wheels not driven by equal tick counts");
}
LOCBENCH_EXPERIMENT_OPTIONS(UmbmarkEffects)

template <class V>
void visit_fields(V& v, UmbmarkOptions& o) {
  v.field("runs", o.runs, "", at_least(1), "Monte-Carlo runs");
  v.coded("scenario", o.scenario, scenario_json, scenario_option, "the robot and the square (datasets/sim)");
  v.field("angle_formula", o.angle_formula, "", Range{}, "UMBmark's angle formula (angle_formula())");
  v.nested("effects", o.effects, "the protocol's effects");
  v.field("validation_waypoints", o.validation_waypoints, "m", any_finite(),
          "an irregular closed validation path, [x, y] each");
}

// An irregular closed path unlike the UMBmark square of side `side` [m], for validation.
std::vector<Eigen::Vector2d> irregular_validation_path(double side);

// The robot's preset, its wheels' drive and a validation path in units of the square's side.
UmbmarkOptions umbmark_defaults(const std::string& preset);

struct UmbmarkSetup {
  sim::Scenario scenario;  // with the effects switched as configured
  baselines::calibration::ClassicUmbmarkOptions classic;
  calibration::ImprovedUmbmarkOptions improved;
  std::vector<Eigen::Vector2d> validation;
  nlohmann::json configuration;
};

// `preset` names the simulator preset of the robot (datasets/sim/presets.h); the experiment is
// "calibration/<preset>".
class CalibrationUmbmark final : public MonteCarloExperiment<UmbmarkOptions, UmbmarkSetup> {
 public:
  explicit CalibrationUmbmark(std::string preset);
  UmbmarkSetup setup(const UmbmarkOptions& o, const McPlan& plan) const override;
  nlohmann::json run_task(const UmbmarkSetup& u, const McPlan& plan, int k) const override;
  reports::ExperimentResults summarise(const UmbmarkSetup& u, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override;

 protected:
  UmbmarkOptions defaults() const override { return umbmark_defaults(preset_); }

 private:
  std::string preset_;
};

}  // namespace locbench::experiments
