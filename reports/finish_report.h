#pragma once
// The tail every verb's report goes through, written once: stamp the provenance, check the
// document against its schema, print the terminal summary, write the file atomically
// (output_file.h) and say "wrote PATH" on the log stream. Used by `locbench run` (full and shard
// reports), `calibrate`, `merge`, `localize`, `match` and `diagnose`.
//
// A schema violation is a bug of the producer, not bad input: std::logic_error (exit 3),
// "PRODUCER produced a report that violates reports/<schema>.schema.json: <first violation>",
// and nothing is written. A file that cannot be written is an InputError naming it (exit 2) and
// leaves any previous file intact. Outputs that would overwrite an input are refused earlier,
// before any work, by check_outputs (output_file.h).
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "reports/report.h"
#include "reports/shard_report.h"

namespace locbench::reports {

// How a verb finishes one report: who made it, from which command line, where it goes; the
// optional parts are set after construction.
struct ReportTail {
  ReportTail(std::string producer_, std::string command_line_, std::filesystem::path path_)
      : producer(std::move(producer_)), command_line(std::move(command_line_)), path(std::move(path_)) {}

  std::string producer;        // names the report in a schema error: "calibrate", "odometry/sim_corridor"
  std::string command_line;    // stamped into the provenance with the build and the time
  std::filesystem::path path;  // where to write; empty: validated (and summarised) but not written
  std::optional<int> threads;  // worker threads, for verbs that have them
  std::optional<int> shards;   // how many shard reports were merged into this one
  std::string wrote_detail;    // said after the path: "3 shards" → "wrote PATH (3 shards)"
  bool print_summary = false;  // the summary table, then every result's and the report's notes
};

// Sets report.provenance, validates (report.schema.json), prints the summary when asked on
// `out`, writes the report (write_report) and logs "wrote PATH" on `log`.
void finish_report(Report& report, const ReportTail& tail, std::ostream& out = std::cout,
                   std::ostream& log = std::cerr);

// The same for a shard report (shard.schema.json, write_shard_report); it has no summary.
void finish_report(ShardReport& shard, const ReportTail& tail, std::ostream& log = std::cerr);

// The same for a diagnosis report (locbench.diagnosis/1, built by algorithms/diagnosis as JSON):
// sets its "provenance" object and validates it against diagnosis.schema.json; no summary.
void finish_report(nlohmann::json& diagnosis, const ReportTail& tail, std::ostream& log = std::cerr);

}  // namespace locbench::reports
