#pragma once
// Scenario ⇄ JSON. Reading is strict: unknown keys and wrong types throw InputError naming the
// key; absent keys keep their defaults (those of Scenario{}, or of the preset named by the
// optional top-level key "preset"). Writing emits every field, so reports can copy a run's
// full configuration and read it back unchanged.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "datasets/sim/scenario.h"

namespace locbench::sim {

nlohmann::json to_json(const Scenario& s);

// `source` names the origin in error messages (a file path, or "<scenario>").
Scenario scenario_from_json(const nlohmann::json& j, const std::string& source = "<scenario>");
// A relative world.file is taken relative to the scenario file's folder.
Scenario load_scenario(const std::filesystem::path& path);

// InputError naming the key and the limit (core/input_limits.h) when the scenario
// would take more time or memory than the limits allow: beams, coordinates, runs, and the
// duration, physics steps and records estimated from its motion program before simulating.
// scenario_from_json calls it.
void check_scenario_limits(const Scenario& s, const std::string& source);
// Robot time [s] the motion program takes: legs at the nominal speeds, turns at the turn rate,
// pauses (what check_scenario_limits bounds).
double estimated_duration(const Scenario& s);

// Enum spellings used in JSON and PARAM records.
const char* to_string(WorldKind k);
const char* to_string(MotionKind k);
const char* to_string(SlipRateUnit u);

}  // namespace locbench::sim
