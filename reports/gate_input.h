#pragma once
// What a gate compares: named series read from locbench reports and Google Benchmark JSON.
#include <map>
#include <set>
#include <string>
#include <vector>

namespace locbench::reports {

struct GateSeries {
  std::string key;         // "<experiment>:<method/dataset/variant>" or "bench:<benchmark name>"
  std::string experiment;  // empty for benchmarks
  std::string dataset;
  std::string unit;
  std::string better = "lower";
  bool is_time = false;  // a Google Benchmark time [ns]: only gated through ratios
  double value = 0.0;    // mean (reports) or median of repetitions (benchmarks)
  std::size_t n = 0;
  double ci95_low = 0.0, ci95_high = 0.0;
  std::vector<double> samples;  // per-run values or per-repetition times, when known
};

struct GateInput {
  std::vector<std::string> sources;
  std::map<std::string, GateSeries> series;
  // experiment → datasets whose cases were skipped (e.g. absent real data).
  std::map<std::string, std::set<std::string>> skipped;
  // Per report file: the git revision that made it and the base seed of its run ("" when the
  // report does not say, e.g. made by `calibrate` or `merge`).
  std::map<std::string, std::string> revision_of, seed_of;
};

// InputError unless every report of `in` comes from one base seed and (with `revisions`) one
// git revision: two runs interleaved in one folder must not pass a gate. `role` names the set
// ("current", "baseline") in the message.
void require_one_run(const GateInput& in, bool revisions, const std::string& role);

// Reads report files, Google Benchmark JSON files, or folders of them (every *.json below).
// InputError naming the file for anything else.
GateInput load_gate_input(const std::vector<std::string>& paths);

}  // namespace locbench::reports
