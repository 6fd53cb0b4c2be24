#pragma once
// Validation of report JSON against reports/report.schema.json (valijson).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace locbench::reports {

// The schema text (embedded at build time).
const char* report_schema_text();
// Every violation as "path: description"; empty when the document is a valid report.
std::vector<std::string> validate_report_json(const nlohmann::json& document);
// The same for shard reports against reports/shard.schema.json.
const char* shard_schema_text();
std::vector<std::string> validate_shard_json(const nlohmann::json& document);
// The same for diagnosis reports (locbench.diagnosis/1) against reports/diagnosis.schema.json.
const char* diagnosis_schema_text();
std::vector<std::string> validate_diagnosis_json(const nlohmann::json& document);

}  // namespace locbench::reports
