#pragma once
// JSON form of the laser baselines' options (SI units, keys = field names), for experiment
// configurations and reports. from_json is strict: absent keys keep their defaults; unknown
// keys, wrong types and invalid values throw UsageError naming the key.
#include <nlohmann/json.hpp>

#include "baselines/laser/extract_then_match.h"

namespace locbench::baselines::laser {

void to_json(nlohmann::json& j, const BreakpointOptions& o);
void from_json(const nlohmann::json& j, BreakpointOptions& o);
void to_json(nlohmann::json& j, const LineAcceptance& o);
void from_json(const nlohmann::json& j, LineAcceptance& o);
void to_json(nlohmann::json& j, const SplitAndMergeOptions& o);
void from_json(const nlohmann::json& j, SplitAndMergeOptions& o);
void to_json(nlohmann::json& j, const AgglomerativeOptions& o);
void from_json(const nlohmann::json& j, AgglomerativeOptions& o);
void to_json(nlohmann::json& j, const RwhtOptions& o);
void from_json(const nlohmann::json& j, RwhtOptions& o);
void to_json(nlohmann::json& j, const LineMatchOptions& o);
void from_json(const nlohmann::json& j, LineMatchOptions& o);
// {"extraction": {...}, "matching": {...}}
void to_json(nlohmann::json& j, const SplitAndMergeMatcherOptions& o);
void from_json(const nlohmann::json& j, SplitAndMergeMatcherOptions& o);
void to_json(nlohmann::json& j, const AgglomerativeMatcherOptions& o);
void from_json(const nlohmann::json& j, AgglomerativeMatcherOptions& o);
void to_json(nlohmann::json& j, const RwhtMatcherOptions& o);
void from_json(const nlohmann::json& j, RwhtMatcherOptions& o);

}  // namespace locbench::baselines::laser
