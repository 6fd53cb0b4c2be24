#pragma once
// What a gate compares: named series read from locbench reports and Google Benchmark JSON.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace locbench::reports {

struct GateSeries {
  std::string key;         // "<experiment>:<method/dataset/variant>" or "bench:<benchmark name>"
  std::string experiment;  // empty for benchmarks
  std::string dataset;
  std::string variant;  // the metric's name (reports); the benchmark's name
  std::string unit;
  std::string better = "lower";
  bool is_time = false;  // a Google Benchmark time [ns]: only gated through ratios
  double value = 0.0;    // mean (reports) or median of repetitions (benchmarks)
  std::size_t n = 0;
  double ci95_low = 0.0, ci95_high = 0.0;
  std::vector<double> samples;     // per-run values or per-repetition times, when known
  std::optional<double> min, max;  // as the report states them (reports only)
  std::string file;                // the report or benchmark file it came from
};

struct GateInput {
  std::vector<std::string> sources;
  std::map<std::string, GateSeries> series;
  // experiment → dataset (the last part of a "skipped" case's name) → the case's reason.
  std::map<std::string, std::map<std::string, std::string>> skipped;
  // experiment → dataset name → path, from each report's `datasets` (what the run read).
  std::map<std::string, std::map<std::string, std::string>> dataset_paths;
  // Per report file: the git revision that made it and the base seed of its run ("" when the
  // report does not say, e.g. made by `calibrate` or `merge`), and its run id ("" in reports made
  // before run ids).
  std::map<std::string, std::string> revision_of, seed_of, run_id_of;
};

// InputError unless every report of `in` comes from one base seed and (with `revisions`) one
// git revision: two runs interleaved in one folder must not pass a gate. `role` names the set
// ("current", "baseline") in the message.
void require_one_run(const GateInput& in, bool revisions, const std::string& role);

// Reads report files, Google Benchmark JSON files, or folders of them (every *.json below).
// InputError naming the file for anything else.
GateInput load_gate_input(const std::vector<std::string>& paths);

}  // namespace locbench::reports
