// `locbench run [EXPERIMENT…]`: run experiments and write one JSON report each.
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_file.h"
#include "core/output_file.h"
#include "datasets/catalog/data_root.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/shard.h"
#include "pipelines/real_log_harness.h"
#include "reports/finish_report.h"
#include "reports/shard_report.h"
#include "reports/summary_table.h"

namespace locbench::cli {
namespace {

struct RunArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::vector<std::string> experiments;
  std::uint64_t seed = 1;
  int runs = 0;
  std::string out = "out";
  std::string config;
  std::vector<std::string> sets;
  std::string data;
  int threads = experiments::hardware_threads();
  std::string shard;                         // "K/N", empty: the whole experiment
  std::string log, relations, ground_truth;  // a user's real log (real_log_harness.h)
  std::string landmark_map, landmark_observations;
  std::vector<std::string> skip_missing;  // dataset names whose absence is accepted ("all": any)
};

// `--set a.b.c=VALUE` → {"a": {"b": {"c": VALUE}}}; VALUE is read as JSON, else as a string.
nlohmann::json parse_set(const std::string& s) {
  const auto eq = s.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw UsageError("--set " + s + ": expected KEY.PATH=VALUE");
  }
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(s.substr(eq + 1));
  } catch (const nlohmann::json::parse_error&) {
    value = s.substr(eq + 1);
  } catch (const nlohmann::json::exception& e) {
    throw UsageError("--set " + s + ": " + e.what() + ": expected a finite number (|x| < 1.8e308)");
  }
  const std::string path = s.substr(0, eq);
  nlohmann::json out = value;
  std::size_t end = path.size();
  while (true) {
    const std::size_t dot = path.rfind('.', end - 1);
    const std::size_t begin = dot == std::string::npos ? 0 : dot + 1;
    out = nlohmann::json{{path.substr(begin, end - begin), out}};
    if (dot == std::string::npos) break;
    end = dot;
  }
  return out;
}

// Experiments named on the command line: exact names, or a group prefix ("odometry" selects
// every "odometry/…"); none selects the default suite.
std::vector<const experiments::Experiment*> select(const std::vector<std::string>& names) {
  std::vector<const experiments::Experiment*> chosen;
  if (names.empty()) {
    for (const auto& e : experiments::all_experiments()) {
      if (e->in_default_suite()) chosen.push_back(e.get());
    }
    return chosen;
  }
  for (const std::string& n : names) {
    std::size_t before = chosen.size();
    for (const auto& e : experiments::all_experiments()) {
      if (e->name() == n || e->name().rfind(n + "/", 0) == 0) chosen.push_back(e.get());
    }
    if (chosen.size() == before) {
      throw UsageError("no experiment named \"" + n + "\" (see `locbench list`)");
    }
  }
  return chosen;
}

// An experiment's "runs" option (from --config or --set) is checked before any work.
void check_runs_option(const experiments::Experiment& e, const nlohmann::json& config, const std::string& file) {
  if (!config.is_object() || !config.contains("runs")) return;
  const nlohmann::json& r = config.at("runs");
  const std::string where = file.empty() ? "--set" : file;
  if (!r.is_number() || !(r.get<double>() >= 1.0) || r.get<double>() != std::floor(r.get<double>())) {
    throw InputError(where, 0, e.name() + ".runs: expected a whole number ≥ 1, found " + r.dump());
  }
  limits::check(r.get<double>(), limits::kMonteCarloRuns, where, e.name() + ".runs");
}

// A skipped case "group/name" is accepted when --skip-missing names "all", the case, or its
// last part (the dataset).
bool skip_allowed(const std::vector<std::string>& names, const std::string& case_name) {
  const std::string dataset = case_name.substr(case_name.rfind('/') + 1);
  for (const std::string& n : names) {
    if (n == "all" || n == case_name || n == dataset) return true;
  }
  return false;
}

std::string args_shard_label(const experiments::Shard& s) { return fmt::format("shard {}/{}", s.index, s.count); }

// The user's files named by a configuration's "datasets" (real_log_harness.h): inputs of the run.
void add_dataset_files(const nlohmann::json& config, std::vector<std::string>& inputs) {
  if (!config.is_object() || !config.contains("datasets") || !config.at("datasets").is_array()) return;
  for (const nlohmann::json& d : config.at("datasets")) {
    if (!d.is_object()) continue;
    for (const char* key : {"log", "relations", "ground_truth"}) {
      if (d.contains(key) && d.at(key).is_string()) inputs.push_back(d.at(key).get<std::string>());
    }
  }
}

nlohmann::json load_overrides(const std::string& path) {
  if (path.empty()) return nlohmann::json::object();
  nlohmann::json j = read_json_file(path, "--config file (JSON)");
  if (!j.is_object()) throw InputError(path, 0, "expected a JSON object keyed by experiment name");
  return j;
}

// Shard K/N of one experiment: its tasks' records → <out>/<experiment>.shard-K-of-N.json.
void run_shard(const experiments::Experiment& e, const nlohmann::json& config, experiments::RunOptions options,
               const experiments::Shard& shard, const std::string& out, const std::string& command_line) {
  reports::ShardReport r;
  r.experiment = e.name();
  r.description = e.description();
  r.configuration = config;
  r.seed = options.seed;
  r.runs = options.runs;
  r.index = shard.index;
  r.count = shard.count;
  r.tasks = e.task_count(config, options);
  const std::vector<int> tasks = experiments::shard_tasks(shard, r.tasks);
  {
    ProgressBar bar(e.name() + " " + args_shard_label(shard));
    options.progress = [&bar](double f) { bar.update(f); };
    const std::vector<nlohmann::json> records =
        tasks.empty() ? std::vector<nlohmann::json>{} : e.run_tasks(config, options, tasks);
    for (std::size_t i = 0; i < tasks.size(); ++i) r.records.push_back({tasks[i], records[i]});
  }
  const auto path =
      std::filesystem::path(out) / fmt::format("{}.shard-{}-of-{}.json", e.name(), shard.index, shard.count);
  reports::ReportTail tail(e.name(), command_line, path);
  tail.threads = options.threads;
  tail.wrote_detail = fmt::format("{} of {} tasks", tasks.size(), r.tasks);
  reports::finish_report(r, tail);
}

// Each --set, parsed once; a key no chosen experiment has is an error.
std::vector<nlohmann::json> parse_sets(const std::vector<std::string>& args_sets,
                                       const std::vector<const experiments::Experiment*>& chosen) {
  std::vector<nlohmann::json> sets;
  for (const std::string& set : args_sets) {
    sets.push_back(parse_set(set));
    const std::string key = sets.back().begin().key();
    bool used = false;
    for (const auto* e : chosen) used = used || e->default_config().contains(key);
    if (!used) throw UsageError("--set " + set + ": no chosen experiment has an option \"" + key + "\"");
  }
  return sets;
}

// --log and its companions, as a configuration override of every chosen experiment (which must
// all take real logs); none without --log.
std::optional<nlohmann::json> log_override_of(const RunArgs& args,
                                              const std::vector<const experiments::Experiment*>& chosen) {
  if (args.log.empty() && (!args.relations.empty() || !args.ground_truth.empty() || !args.landmark_map.empty() ||
                           !args.landmark_observations.empty())) {
    throw UsageError("--relations, --ground-truth, --landmark-map and --landmark-observations need --log");
  }
  const auto log_override = experiments::real_log_cli_override(args.log, args.relations, args.ground_truth,
                                                               args.landmark_map, args.landmark_observations);
  if (log_override) {
    for (const auto* e : chosen) {
      if (!experiments::takes_real_logs(e->default_config())) {
        throw UsageError("--log: experiment " + e->name() + " does not take real logs");
      }
    }
  }
  return log_override;
}

experiments::RunOptions run_options_of(const RunArgs& args) {
  experiments::RunOptions options;
  options.seed = args.seed;
  if (args.runs > 0) options.runs = args.runs;
  options.data_root = args.data.empty() ? catalog::data_root() : std::filesystem::path(args.data);
  if (!args.data.empty() && !std::filesystem::is_directory(options.data_root)) {
    throw InputError(args.data, 0, "--data: no such folder (the datasets' folder, see `locbench list`)");
  }
  options.threads = args.threads;
  return options;
}

// Each chosen experiment's configuration: its defaults, the --config file's part, every --set
// whose key it has, the --log override; the dataset files it names join `inputs`.
std::vector<nlohmann::json> configs_of(const std::vector<const experiments::Experiment*>& chosen,
                                       const nlohmann::json& overrides, const std::vector<nlohmann::json>& sets,
                                       const std::optional<nlohmann::json>& log_override, const RunArgs& args,
                                       std::vector<std::string>& inputs) {
  std::vector<nlohmann::json> configs;
  for (const experiments::Experiment* e : chosen) {
    nlohmann::json config = e->default_config();
    if (overrides.contains(e->name())) {
      try {
        config = experiments::merge_config(config, overrides.at(e->name()));
      } catch (const UsageError& err) {
        throw InputError(args.config, 0, err.what());  // name the file the option came from
      }
    }
    // --set applies to every chosen experiment whose options have the key's first part.
    for (const nlohmann::json& o : sets) {
      if (config.contains(o.begin().key())) config = experiments::merge_config(config, o);
    }
    if (log_override) config = experiments::merge_config(config, *log_override);
    check_runs_option(*e, config, args.config);
    add_dataset_files(config, inputs);
    configs.push_back(std::move(config));
  }
  return configs;
}

// The cases of the reports that did not run: skipped for missing data (accepted by
// --skip-missing or not) and failed.
struct CaseOutcomes {
  std::vector<std::string> missing;   // skipped cases not accepted by --skip-missing
  std::vector<std::string> accepted;  // skipped cases --skip-missing accepted
  std::vector<std::string> failed;    // cases that ran and failed (unreadable data, …)
};

void sort_cases(const reports::ExperimentResults& body, const std::vector<std::string>& skip_missing,
                CaseOutcomes& cases) {
  for (const reports::CaseNote& c : body.cases) {
    if (c.status == "skipped") {
      (skip_allowed(skip_missing, c.name) ? cases.accepted : cases.missing).push_back(c.name + ": " + c.reason);
    } else {
      cases.failed.push_back(c.name + ": " + c.reason);
    }
  }
}

// Says on stderr what did not run, and returns the exit code: a user's bad file or unaccepted
// missing data, 2; else a failed case, 1.
int report_case_outcomes(const CaseOutcomes& cases, int exit_code) {
  if (!cases.accepted.empty()) {
    std::cerr << "locbench: " << cases.accepted.size()
              << " case(s) skipped for missing data, accepted by --skip-missing:\n";
    for (const std::string& m : cases.accepted) std::cerr << "  " << m << '\n';
  }
  if (!cases.failed.empty()) {
    // Fail closed: a case that ran and failed (an unreadable log, a missing file of a catalog
    // dataset, no relations where they are needed) is a failed run, even when its report was written.
    std::cerr << "locbench: error: " << cases.failed.size() << " case(s) failed:\n";
    for (const std::string& f : cases.failed) std::cerr << "  " << f << '\n';
  }
  if (!cases.missing.empty()) {
    // Fail closed: a run whose data went missing must not look like a run that passed.
    std::cerr << "locbench: error: " << cases.missing.size() << " case(s) skipped for missing data (pass "
              << "--skip-missing NAME, or --skip-missing all, to accept):\n";
    for (const std::string& m : cases.missing) std::cerr << "  " << m << '\n';
  }
  if (exit_code != kExitOk || !cases.missing.empty()) return kExitBadInput;
  return cases.failed.empty() ? kExitOk : kExitCheckFailed;
}

int run(const RunArgs& args, const std::string& command_line) {
  const auto chosen = select(args.experiments);
  const nlohmann::json overrides = load_overrides(args.config);
  const std::vector<nlohmann::json> sets = parse_sets(args.sets, chosen);
  for (const auto& [name, value] : overrides.items()) {
    if (!experiments::find_experiment(name)) {
      throw InputError(args.config, 0, "configuration for unknown experiment \"" + name + "\"");
    }
  }
  const auto log_override = log_override_of(args, chosen);
  experiments::RunOptions options = run_options_of(args);
  std::optional<experiments::Shard> shard;
  if (!args.shard.empty()) shard = experiments::parse_shard(args.shard);

  std::vector<std::string> inputs = {args.config, args.log, args.relations, args.ground_truth};
  const std::vector<nlohmann::json> configs = configs_of(chosen, overrides, sets, log_override, args, inputs);
  // Every input file takes part in the overlap check: none may lie in the folder the run writes.
  check_inputs_outside(inputs, args.out, "--out");
  const OutputFolderLock lock(args.out);

  std::vector<reports::Report> written;
  CaseOutcomes cases;
  int exit_code = kExitOk;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const experiments::Experiment* e = chosen[i];
    const nlohmann::json& config = configs[i];
    if (shard) {
      run_shard(*e, config, options, *shard, args.out, command_line);
      continue;
    }
    reports::Report report;
    {
      ProgressBar bar(e->name());
      options.progress = [&bar](double f) { bar.update(f); };
      try {
        report.body = e->run(config, options);
      } catch (const InputError& err) {
        std::cerr << "locbench: " << e->name() << ": error: " << err.what() << '\n';
        exit_code = kExitBadInput;
        continue;
      }
    }
    sort_cases(report.body, args.skip_missing, cases);
    reports::ReportTail tail(e->name(), command_line, std::filesystem::path(args.out) / (e->name() + ".json"));
    tail.threads = options.threads;
    reports::finish_report(report, tail);
    written.push_back(std::move(report));
  }
  if (!shard) std::cout << reports::summary_table(written);
  return report_case_outcomes(cases, exit_code);
}

}  // namespace

Action add_run_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] =
      add_verb<RunArgs>(app, "run", "Run experiments (default: the default suite) and write JSON reports");
  cmd->add_option("experiments", args->experiments,
                  "Experiment names or groups (e.g. odometry/sim_corridor, odometry)");
  add_seed_option(cmd, args->seed, "Base seed of every random run")->capture_default_str();
  cmd->add_option("--runs", args->runs, "Monte-Carlo runs, 1 … 100000 (default: each experiment's own)")
      ->check(CLI::Range(1, static_cast<int>(limits::kMonteCarloRuns.max)));
  cmd->add_option("-o,--out", args->out, "Folder for reports")->capture_default_str();
  cmd->add_option("--config", args->config, "JSON file {\"experiment/name\": {option: value}} overriding defaults");
  cmd->add_option("--set", args->sets,
                  "Override one option, KEY.PATH=VALUE (JSON value), e.g. "
                  "filters.sage_husa_aekf.forgetting=0.95; repeatable");
  add_threads_option(cmd, args->threads,
                     "Worker threads for Monte-Carlo runs (default: all cores); results are the same for any number")
      ->capture_default_str();
  cmd->add_option("--shard", args->shard,
                  "Run only shard K of N (tasks i with i mod N = K-1) and write "
                  "<out>/<experiment>.shard-K-of-N.json for `locbench merge`")
      ->type_name("K/N");
  add_data_option(cmd, args->data);
  cmd->add_option("--log", args->log,
                  "Run the real-data experiments on this log instead of the catalog's "
                  "(CARMEN .clf[.gz], MRCLAM folder[#robotN])");
  cmd->add_option("--relations", args->relations, "With --log: reference relations (.relations[.gz])");
  cmd->add_option("--ground-truth", args->ground_truth, "With --log: ground truth (TUM format)");
  cmd->add_option("--landmark-map", args->landmark_map,
                  "With --log: landmark map, one `id x y [sigma_x sigma_y]` [m] per line (replaces an "
                  "MRCLAM folder's Landmark_Groundtruth.dat)");
  cmd->add_option("--landmark-observations", args->landmark_observations,
                  "With --log: landmark observations, one `t id range bearing` [s, -, m, rad] per line, ids "
                  "from the landmark map");
  cmd->add_option("--skip-missing", args->skip_missing,
                  "Accept that this dataset (or case, or \"all\") is absent; otherwise a case skipped "
                  "for missing data fails the run (exit 2); repeatable");
  return bag_topic_action(cmd, args, &RunArgs::log, [command_line](const RunArgs& a) { return run(a, command_line); });
}

}  // namespace locbench::cli
