#pragma once
// Report ⇄ JSON (schema: reports/report.schema.json) and writing report files.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "reports/report.h"

namespace locbench::reports {

nlohmann::json to_json(const Report& report);
// The experiment's part of a report (everything but "schema" and "context"), and back; used to
// carry a whole experiment's results as one shard record and to compare results exactly.
nlohmann::json results_to_json(const ExperimentResults& results);
ExperimentResults results_from_json(const nlohmann::json& j, const std::string& source);
// The "context" object, and back (InputError naming `source` on a missing or mistyped field).
nlohmann::json provenance_to_json(const Provenance& provenance);
Provenance provenance_from_json(const nlohmann::json& context, const std::string& source);
// Parses a report written by to_json; InputError (naming `source`) on a missing or mistyped field.
Report report_from_json(const nlohmann::json& j, const std::string& source);

// Writes the report as indented JSON, creating parent folders; returns the path written.
std::filesystem::path write_report(const Report& report, const std::filesystem::path& path);
// Reads and parses a report file.
Report read_report(const std::filesystem::path& path);

}  // namespace locbench::reports
