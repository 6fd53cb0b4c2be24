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
  // "ok", "improved", "regressed", "missing", "skipped", "new", "info" (times: no rule),
  // "invalid" (a number no measurement gives, gate_checks.h), "mixed" (reports of two runs)
  std::string status;
  std::string detail;
};

struct GateRatioRow {
  std::string name;
  std::optional<double> old_ratio, new_ratio;  // medians
  std::optional<double> relative_change;
  std::optional<double> p_value;  // Mann–Whitney, H1: the ratio grew
  std::string status;             // "ok", "improved", "regressed", "missing", "invalid"
  std::string detail;
};

struct GateVerdict {
  std::vector<GateRow> rows;
  std::vector<GateRatioRow> ratios;
  std::optional<double> geomean_ratio;  // geometric mean of new/old over positive pairs
  std::size_t failures = 0;
  bool passed() const { return failures == 0; }
};

// Fails closed (gate_checks.h): a series no measurement gives fails ("invalid"), a missing
// result counts as skipped only when the skip is backed by provenance, and a baseline with
// results from recorded data fails when none of them was compared now.
GateVerdict evaluate_gate(const GateInput& baseline, const GateInput& current, const GateRules& rules);

// Adds a failing row "run id" when the current reports carry different run ids (a run killed
// over a folder of an older one).
void fail_mixed_runs(const GateInput& current, GateVerdict& v);

// A plain table (stdout), a Markdown summary (CI logs) and a JSON verdict.
std::string gate_table(const GateVerdict& v);
std::string gate_markdown(const GateVerdict& v);
nlohmann::json gate_json(const GateVerdict& v, const GateInput& baseline, const GateInput& current);

}  // namespace locbench::reports
