#pragma once
// A simulator scenario as an experiment's option (experiment_framework/experiment_options.h `coded`):
//   v.coded("scenario", o.scenario, scenario_json, scenario_option, "…");
// written by sim::to_json and read back, checked, by sim::scenario_from_json.
#include <nlohmann/json.hpp>

#include "datasets/sim/scenario.h"
#include "datasets/sim/scenario_json.h"

namespace locbench::experiments {

inline nlohmann::json scenario_json(const sim::Scenario& s) { return sim::to_json(s); }
inline sim::Scenario scenario_option(const nlohmann::json& j) { return sim::scenario_from_json(j, "<configuration>"); }

}  // namespace locbench::experiments
