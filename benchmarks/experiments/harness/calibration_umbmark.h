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
#include "benchmarks/experiments/framework/monte_carlo.h"
#include "datasets/sim/scenario.h"

namespace locbench::experiments {

struct UmbmarkSetup {
  sim::Scenario scenario;  // with the effects switched as configured
  ClassicUmbmarkOptions classic;
  ImprovedUmbmarkOptions improved;
  std::vector<Eigen::Vector2d> validation;
  nlohmann::json configuration;
};

// `preset` names the simulator preset of the robot (datasets/sim/presets.h); the experiment is
// "calibration/<preset>".
class CalibrationUmbmark final : public MonteCarloExperiment<UmbmarkSetup> {
 public:
  explicit CalibrationUmbmark(std::string preset);
  std::string name() const override;
  std::string description() const override;
  nlohmann::json default_config() const override;
  UmbmarkSetup setup(const nlohmann::json& config, const McPlan& plan) const override;
  nlohmann::json run_task(const UmbmarkSetup& u, const McPlan& plan, int k) const override;
  reports::ExperimentResults summarise(const UmbmarkSetup& u, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override;

 private:
  std::string preset_;
};

}  // namespace locbench::experiments
