// `locbench merge SHARD… -o OUT`: rebuilds full reports from the shard reports of
// `locbench run EXPERIMENT --shard K/N`, through the experiment's own summary step, so the result
// equals a single-machine run with the same seed and runs. Refuses shards that do not belong
// together (exit code 2).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/json_file.h"
#include "core/output_file.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/parallel_tasks.h"
#include "experiment_framework/shard.h"
#include "reports/finish_report.h"
#include "reports/provenance.h"
#include "reports/schema_validation.h"
#include "reports/shard_report.h"
#include "reports/summary_table.h"

namespace locbench::cli {
namespace {

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string out;
  int threads = experiments::hardware_threads();
};

struct ShardFile {
  std::string path;
  reports::ShardReport shard;
};

ShardFile load_shard(const std::filesystem::path& path) {
  const nlohmann::json j = read_json_file(path, "shard report (JSON)");
  if (j.is_object() && j.value("schema", "") == reports::kReportSchema) {
    throw InputError(path.string(), 0, "a full report, not a shard report (made by `locbench run --shard K/N`)");
  }
  if (const auto errors = reports::validate_shard_json(j); !errors.empty()) {
    throw InputError(path.string(), 0, "not a valid shard report: " + errors.front());
  }
  return {path.string(), reports::shard_report_from_json(j, path.string())};
}

// Files as given; a folder contributes its *.shard-K-of-N.json files.
std::vector<ShardFile> load_shards(const std::vector<std::string>& inputs) {
  std::vector<ShardFile> files;
  for (const std::string& in : inputs) {
    const std::filesystem::path p(in);
    if (std::filesystem::is_directory(p)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(p)) {
        const std::string n = entry.path().filename().string();
        if (entry.is_regular_file() && n.find(".shard-") != std::string::npos && n.ends_with(".json")) {
          found.push_back(entry.path());
        }
      }
      if (found.empty()) throw InputError(in, 0, "folder holds no *.shard-K-of-N.json files");
      std::sort(found.begin(), found.end());
      for (const auto& f : found) files.push_back(load_shard(f));
    } else {
      files.push_back(load_shard(p));
    }
  }
  return files;
}

// Every way shards can fail to belong together, as an InputError naming the file.
void check_consistent(const std::vector<const ShardFile*>& group) {
  const ShardFile& a = *group.front();
  const reports::ShardReport& s = a.shard;
  const auto differs = [&](const ShardFile& f, const std::string& what, const std::string& mine,
                           const std::string& theirs) {
    throw InputError(f.path, 0,
                     fmt::format("{} differs from {}'s ({} vs {}): shards of different runs "
                                 "cannot be merged",
                                 what, a.path, theirs, mine));
  };
  for (const ShardFile* f : group) {
    const reports::ShardReport& t = f->shard;
    if (t.seed != s.seed) differs(*f, "seed", std::to_string(s.seed), std::to_string(t.seed));
    if (t.runs != s.runs) {
      const auto str = [](const std::optional<int>& r) { return r ? std::to_string(*r) : "default"; };
      differs(*f, "--runs", str(s.runs), str(t.runs));
    }
    if (t.configuration != s.configuration) differs(*f, "configuration", "…", "…");
    if (t.provenance.git_revision != s.provenance.git_revision) {
      differs(*f, "git revision", s.provenance.git_revision, t.provenance.git_revision);
    }
    if (t.provenance.tool_version != s.provenance.tool_version) {
      differs(*f, "tool version", s.provenance.tool_version, t.provenance.tool_version);
    }
    if (t.count != s.count) differs(*f, "shard count N", std::to_string(s.count), std::to_string(t.count));
    if (t.tasks != s.tasks) differs(*f, "task count", std::to_string(s.tasks), std::to_string(t.tasks));
  }
  std::map<int, const ShardFile*> by_index;
  for (const ShardFile* f : group) {
    const auto [it, fresh] = by_index.emplace(f->shard.index, f);
    if (!fresh) {
      throw InputError(
          f->path, 0,
          fmt::format("shard {}/{} given twice (also {})", f->shard.index, f->shard.count, it->second->path));
    }
    std::vector<int> got;
    for (const auto& r : f->shard.records) got.push_back(r.task);
    const experiments::Shard sh{f->shard.index, f->shard.count};
    if (sh.index < 1 || sh.index > sh.count || got != experiments::shard_tasks(sh, f->shard.tasks)) {
      throw InputError(f->path, 0,
                       fmt::format("shard {}/{} does not hold the tasks i with i mod {} = {}", sh.index, sh.count,
                                   sh.count, sh.index - 1));
    }
  }
  for (int k = 1; k <= s.count; ++k) {
    if (!by_index.count(k)) {
      throw InputError(a.path, 0, fmt::format("{}: shard {}/{} is missing", s.experiment, k, s.count));
    }
  }
}

reports::Report merge_group(const std::vector<const ShardFile*>& group, int threads, const std::string& command_line) {
  check_consistent(group);
  const reports::ShardReport& s = group.front()->shard;
  const reports::Provenance here = reports::current_provenance(command_line);
  if (here.git_revision != s.provenance.git_revision) {
    throw InputError(group.front()->path, 0,
                     "made by git revision " + s.provenance.git_revision + ", but this locbench is " +
                         here.git_revision + ": merge with the build that made the shards");
  }
  const experiments::Experiment* e = experiments::find_experiment(s.experiment);
  if (!e) throw InputError(group.front()->path, 0, "unknown experiment \"" + s.experiment + "\"");
  experiments::RunOptions options;
  options.seed = s.seed;
  options.runs = s.runs;
  options.threads = threads;
  if (e->task_count(s.configuration, options) != s.tasks) {
    throw InputError(group.front()->path, 0,
                     fmt::format("{} has {} tasks here, the shards say {}", s.experiment,
                                 e->task_count(s.configuration, options), s.tasks));
  }
  std::vector<nlohmann::json> records(static_cast<std::size_t>(s.tasks));
  for (const ShardFile* f : group) {
    for (const auto& r : f->shard.records) records[static_cast<std::size_t>(r.task)] = r.record;
  }
  reports::Report report;
  try {
    report.body = e->summarise_records(s.configuration, options, records);
  } catch (const nlohmann::json::exception& err) {
    throw InputError(group.front()->path, 0,
                     s.experiment + ": a record does not have the shape this experiment writes (" + err.what() +
                         "): expected the shards `locbench run --shard` made");
  }
  return report;
}

int merge(const MergeArgs& args, const std::string& command_line) {
  const bool to_file = args.out.ends_with(".json");
  check_outputs(args.inputs, {{"-o", to_file ? args.out : ""}}, ".json");
  // -o takes the output folder's lock like `run --out`; a report file, the locks of the folders
  // above it (a folder `run --out` is writing is refused, not written into).
  std::optional<OutputFolderLock> lock;
  std::vector<std::unique_ptr<OutputFolderLock>> locks_above;
  if (to_file) {
    locks_above = lock_folders_above(args.out);
  } else {
    lock.emplace(args.out);
  }
  const std::vector<ShardFile> files = load_shards(args.inputs);
  std::map<std::string, std::vector<const ShardFile*>> groups;
  for (const ShardFile& f : files) groups[f.shard.experiment].push_back(&f);
  const bool single_file = groups.size() == 1 && args.out.ends_with(".json");
  if (groups.size() > 1 && args.out.ends_with(".json")) {
    throw UsageError(
        fmt::format("the shards hold {} experiments: -o must be a folder, not {}", groups.size(), args.out));
  }
  std::vector<reports::Report> written;
  for (const auto& [name, group] : groups) {
    reports::Report report = merge_group(group, args.threads, command_line);
    reports::ReportTail tail(
        "merge of " + name, command_line,
        single_file ? std::filesystem::path(args.out) : std::filesystem::path(args.out) / (name + ".json"));
    tail.threads = args.threads;
    tail.shards = group.front()->shard.count;
    tail.wrote_detail = fmt::format("{} shards", group.size());
    reports::finish_report(report, tail);
    written.push_back(std::move(report));
  }
  std::cout << reports::summary_table(written);
  return kExitOk;
}

}  // namespace

Action add_merge_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] =
      add_verb<MergeArgs>(app, "merge", "Merge shard reports (locbench run --shard K/N) into full reports");
  cmd->add_option("shards", args->inputs, "Shard reports, or folders holding them")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("-o,--out", args->out, "Report file (one experiment, ends in .json) or folder (one report each)")
      ->required();
  add_threads_option(cmd, args->threads, "Worker threads for any work of the summary step")->capture_default_str();
  return [args = args, command_line] { return merge(*args, command_line); };
}

}  // namespace locbench::cli
