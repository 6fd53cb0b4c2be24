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
Scenario load_scenario(const std::filesystem::path& path);

// Enum spellings used in JSON and PARAM records.
const char* to_string(WorldKind k);
const char* to_string(MotionKind k);
const char* to_string(SlipRateUnit u);

}  // namespace locbench::sim
