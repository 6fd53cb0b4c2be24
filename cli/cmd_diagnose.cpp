// `locbench diagnose LOG [--relations R] [--report out.json] [--scenario twin.json]`: what the nominal model a log
// declares gets wrong — residual tests, named causes with fitted parameters and 95% intervals,
// held-out gain, unexplained structure, verdict (algorithms/diagnosis/diagnosis.h).
// LOG is a CARMEN log (ENCODER/ODOM with TRUEPOS or COMPASS), an MRCLAM folder (#robotN), a
// catalog dataset name (`locbench list`: aces, intel, mrclam6_robot1, …), or a histogram JSON.
// --scenario writes the log's synthetic twin under the extended model (the nominal model plus
// every kept cause) as a simulator scenario (pipelines/twin/twin_scenario.h).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "algorithms/diagnosis/diagnosis.h"
#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_file.h"
#include "core/output_file.h"
#include "datasets/catalog/data_root.h"
#include "datasets/catalog/log_spec.h"
#include "datasets/io/data_lines.h"
#include "datasets/sim/scenario_json.h"
#include "pipelines/twin/twin_scenario.h"
#include "reports/finish_report.h"

namespace locbench::cli {
namespace {

struct DiagnoseArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::string input;
  std::string relations;
  std::string report;
  std::string scenario;
  std::string data;
  double false_alarm = 0.01;
  double window = 1.0;
  double max_records = limits::kDiagnoseOdometryRecords.max;
};

bool ends_with(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

void print(const diagnosis::Diagnosis& d) {
  std::cout << "log:       " << d.log << "\nreference: " << d.reference << "\n";
  std::size_t failed = 0;
  for (const auto& t : d.residual_tests) failed += t.passed ? 0 : 1;
  std::cout << fmt::format("residual tests: {} of {} significant\n", failed, d.residual_tests.size());
  for (const auto& t : d.residual_tests) {
    if (!t.passed) {
      std::cout << fmt::format("  {:<22} {:<20} {:<18} {}={:.4g} p={:.3g}\n", t.name, t.residual, t.variable,
                               t.statistic, t.value, t.p_value);
    }
  }
  for (const auto& c : d.causes) {
    if (!c.detected) continue;
    std::cout << fmt::format("cause {:<22} {} = {:.4g} (threshold {:.4g}){}\n", c.id, c.statistic, c.value, c.threshold,
                             c.identifiable ? "" : " — confounded");
    for (const auto& p : c.parameters) {
      std::cout << fmt::format("  {:<12} {:.6g}  95% [{:.6g}, {:.6g}]\n", p.name, p.value, p.lo, p.hi);
    }
    for (const auto& [k, v] : c.extra.items()) std::cout << fmt::format("  {:<12} {}\n", k, v.dump());
    if (!c.gains.empty()) {
      const auto& g = c.gains.front();
      std::cout << fmt::format("  gain {}: {:.6g} → {:.6g} ({:+.1f}%)\n", g.metric, g.before, g.after,
                               100.0 * g.relative());
    }
  }
  for (const auto& g : d.confounded) std::cout << "confounded: " << g.combination << "\n";
  for (const auto& id : d.unconfirmed) {
    std::cout << "unconfirmed: " << id << " (likelihood ratio passed on training windows, no held-out gain)\n";
  }
  for (const auto& u : d.unexplained) {
    std::cout << fmt::format("unexplained: {} of {} against {} (statistic {:.4g}, p = {:.3g})\n", u.test, u.residual,
                             u.variable.empty() ? "-" : u.variable, u.statistic, u.p_value);
  }
  std::cout << "verdict: " << d.verdict << std::endl;
}

void print_twin(const sim::Twin& twin) {
  for (const auto& m : twin.causes) {
    std::cout << fmt::format("twin: {:<22} {}\n", m.id, m.how);
  }
  if (twin.causes.empty()) std::cout << "twin: no cause kept — the extended twin is the nominal one\n";
  if (!twin.not_simulated.empty()) {
    std::string ids;
    for (const auto& id : twin.not_simulated) ids += (ids.empty() ? "" : ", ") + id;
    std::cout << "twin: NOT simulated (kept but without a simulator mapping): " << ids << "\n";
  }
  const auto& n = twin.extended.motion_noise;
  std::cout << fmt::format("twin: noise floor per {:g} s window σ_x = {:.4g} m, σ_y = {:.4g} m, σ_θ = {:.4g} rad\n",
                           n.window, n.sigma_along, n.sigma_left, n.sigma_heading);
}

int diagnose(const DiagnoseArgs& a, const std::string& command_line) {
  diagnosis::DiagnosisOptions opt;
  opt.false_alarm = a.false_alarm;
  opt.windows.duration = a.window;
  if (!(a.false_alarm >= 1e-12 && a.false_alarm < 0.5)) {
    throw UsageError(fmt::format("--false-alarm {}: expected a level in [1e-12, 0.5)", a.false_alarm));
  }
  if (!(a.window > 0.0 && a.window <= 3600.0)) {
    throw UsageError(fmt::format("--window {}: expected a length in (0, 3600] s", a.window));
  }
  check_outputs({a.input, a.relations}, {{"--report", a.report}, {"--scenario", a.scenario}});
  diagnosis::Diagnosis d;
  DatasetRef input;
  std::optional<Log> log_read;
  if (ends_with(a.input, ".json")) {
    if (!a.scenario.empty()) {
      throw UsageError("--scenario needs a log: a histogram of residuals has no motion to replay");
    }
    const nlohmann::json j = read_json_file(a.input, "residual histogram (JSON)");
    const diagnosis::ResidualHistogram h = diagnosis::read_histogram(j, a.input);
    d = diagnosis::diagnose_histogram(h, a.input, opt);
    input = {a.input, a.input, file_checksum(a.input), h.counts.size(), 0.0};
  } else {
    catalog::LogSpec spec;
    spec.log = a.input;
    spec.relations = a.relations;
    auto loaded = catalog::load_log_spec(spec, a.data.empty() ? catalog::data_root() : std::filesystem::path(a.data));
    Log& log = loaded.log;
    // ~0.2 ms a record: a log file is refused before the fits unless --max-records raises the limit.
    const double records = static_cast<double>(log.encoders.size() + log.odometry.size());
    if (loaded.entry == nullptr && records > a.max_records) {
      limits::check(records,
                    {limits::kDiagnoseOdometryRecords.key, a.max_records, limits::kDiagnoseOdometryRecords.why},
                    a.input, "odometry records (ENCODER, ODOM)");
    }
    if (log.source.empty()) log.source = a.input;
    d = diagnosis::diagnose_log(log, opt);
    input = loaded.dataset;
    log_read = std::move(log);
  }
  print(d);
  if (!a.scenario.empty()) {
    const sim::Twin twin = sim::build_twin(*log_read, d);
    print_twin(twin);
    write_file_atomically(a.scenario, sim::to_json(twin.extended).dump(2) + "\n");
    std::cerr << "wrote " << a.scenario << " (simulate it with `locbench simulate " << a.scenario << " -o twin.clf`)\n";
  }
  if (!a.report.empty()) {
    nlohmann::json j = diagnosis::to_json(d);
    j["input"] = {{"name", input.name},
                  {"path", input.path},
                  {"checksum", input.checksum},
                  {"records", input.records},
                  {"duration_s", input.duration_s}};
    nlohmann::json options;
    diagnosis::to_json(options, opt);
    j["configuration"] = options;
    reports::finish_report(j, reports::ReportTail("diagnose", command_line, a.report));
  }
  return kExitOk;
}

}  // namespace

Action add_diagnose_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] = add_verb<DiagnoseArgs>(
      app, "diagnose",
      "What the nominal model of a log gets wrong: residual tests, named causes, fitted extensions, gain");
  cmd->add_option("input", args->input,
                  "A log (CARMEN .clf[.gz] with ENCODER or ODOM and TRUEPOS/COMPASS; MRCLAM folder#robotN), "
                  "a catalog dataset name, or a residual histogram (.json)")
      ->required();
  cmd->add_option("--relations", args->relations, "Reference relations for the log's ODOM (.relations[.gz])");
  cmd->add_option("--report", args->report, "Write the diagnosis (locbench.diagnosis/1 JSON) here");
  cmd->add_option("--scenario", args->scenario,
                  "Write the log's synthetic twin (its odometry replayed under the nominal model plus every kept "
                  "cause) as a simulator scenario JSON for `locbench simulate`");
  cmd->add_option("--false-alarm", args->false_alarm,
                  "False-alarm level per log and channel, in [1e-12, 0.5) (default 0.01)");
  cmd->add_option("--window", args->window, "Residual window length [s], in (0, 3600] (default 1)");
  cmd->add_option("--max-records", args->max_records,
                  "Diagnose a log file with more odometry records than the limit (~0.2 ms each; catalog datasets "
                  "are exempt)")
      ->check(CLI::Range(1.0, 1e8));
  add_data_option(cmd, args->data);
  return bag_topic_action(cmd, args, &DiagnoseArgs::input,
                          [command_line](const DiagnoseArgs& a) { return diagnose(a, command_line); });
}

}  // namespace locbench::cli
