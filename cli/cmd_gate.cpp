// `locbench gate CURRENT… --baseline BASELINE… [--rules RULES.json]`: fail (exit 1) when a
// result got worse than the rules allow.
#include <iostream>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/output_file.h"
#include "reports/gate.h"

namespace locbench::cli {
namespace {

struct GateArgs {
  std::vector<std::string> current;
  std::vector<std::string> baseline;
  std::string rules;
  std::string markdown;
  std::string json;
  bool allow_mixed = false;
};

int gate(const GateArgs& args) {
  std::vector<std::string> inputs = args.current;
  inputs.insert(inputs.end(), args.baseline.begin(), args.baseline.end());
  inputs.push_back(args.rules);
  check_outputs(inputs, {{"--markdown", args.markdown}, {"--json", args.json}}, ".json");
  const reports::GateInput baseline = reports::load_gate_input(args.baseline);
  const reports::GateInput current = reports::load_gate_input(args.current);
  // Fail closed: nothing to compare against, or two runs mixed in one set, is an error.
  if (baseline.series.empty()) {
    throw InputError(args.baseline.front(), 0, "the baseline holds no results: a gate against nothing cannot pass");
  }
  if (!args.allow_mixed) {
    reports::require_one_run(current, true, "current");
    // A committed baseline is refreshed experiment by experiment: its revisions may differ.
    reports::require_one_run(baseline, false, "baseline");
  }
  const reports::GateRules rules =
      args.rules.empty() ? reports::default_gate_rules() : reports::load_gate_rules(args.rules);
  reports::GateVerdict verdict = reports::evaluate_gate(baseline, current, rules);
  // One run id per current folder (a committed baseline is refreshed experiment by experiment:
  // its reports may carry different ids, or none).
  if (!args.allow_mixed) reports::fail_mixed_runs(current, verdict);
  std::cout << reports::gate_table(verdict);
  if (!args.markdown.empty()) write_file_atomically(args.markdown, reports::gate_markdown(verdict));
  if (!args.json.empty()) {
    write_file_atomically(args.json, reports::gate_json(verdict, baseline, current).dump(2) + "\n");
  }
  return verdict.passed() ? kExitOk : kExitCheckFailed;
}

}  // namespace

Action add_gate_command(CLI::App& app) {
  const auto [cmd, args] = add_verb<GateArgs>(
      app, "gate", "Compare reports (or Google Benchmark JSON) with a baseline; exit 1 on regression");
  cmd->add_option("current", args->current, "Current reports: files or folders of *.json")->required();
  cmd->add_option("--baseline", args->baseline, "Baseline reports: files or folders")->required();
  cmd->add_option("--rules", args->rules,
                  "Rules JSON (default: every result may worsen by 5% and must leave its 95% "
                  "interval to fail)");
  cmd->add_option("--markdown", args->markdown, "Also write a Markdown summary (for CI logs)");
  cmd->add_option("--json", args->json, "Also write the verdict as JSON");
  cmd->add_flag("--allow-mixed", args->allow_mixed,
                "Compare reports of different base seeds (or, among the current ones, git revisions or "
                "run ids); refused by default");
  return [args = args] { return gate(*args); };
}

}  // namespace locbench::cli
