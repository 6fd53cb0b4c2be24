#pragma once
// Compares current results with a baseline the way Google Benchmark's compare tool does —
// matched by stable name, old, new, (new − old)/|old|, a geometric-mean row — and applies
// the rules: accuracy may not get worse than allowed; speed ratios measured within one run
// may not grow (Mann–Whitney U over repetitions before calling it a regression).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "reports/gate_input.h"
#include "reports/gate_rules.h"

namespace locbench::reports {

struct GateRow {
  std::string key;
  std::string unit;
  std::optional<double> old_value, new_value;
  std::optional<double> relative_change;  // (new − old)/|old|
  // "ok", "improved", "regressed", "missing", "skipped", "new", "info" (times: no rule)
  std::string status;
  std::string detail;
};

struct GateRatioRow {
  std::string name;
  std::optional<double> old_ratio, new_ratio;  // medians
  std::optional<double> relative_change;
  std::optional<double> p_value;  // Mann–Whitney, H1: the ratio grew
  std::string status;             // "ok", "improved", "regressed", "missing"
  std::string detail;
};

struct GateVerdict {
  std::vector<GateRow> rows;
  std::vector<GateRatioRow> ratios;
  std::optional<double> geomean_ratio;  // geometric mean of new/old over positive pairs
  std::size_t failures = 0;
  bool passed() const { return failures == 0; }
};

GateVerdict evaluate_gate(const GateInput& baseline, const GateInput& current, const GateRules& rules);

// A plain table (stdout), a Markdown summary (CI logs) and a JSON verdict.
std::string gate_table(const GateVerdict& v);
std::string gate_markdown(const GateVerdict& v);
nlohmann::json gate_json(const GateVerdict& v, const GateInput& baseline, const GateInput& current);

}  // namespace locbench::reports
