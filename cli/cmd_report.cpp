// `locbench report REPORT.json… -o report.html`: one self-contained HTML page with the tables
// and charts of the given reports (charts drawn by gnuplot, inlined as SVG).
#include <algorithm>
#include <iostream>
#include <set>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/json_file.h"
#include "core/output_file.h"
#include "experiment_framework/experiment.h"
#include "reports/gnuplot_svg.h"
#include "reports/html_report.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "reports/shard_report.h"

namespace locbench::cli {
namespace {

struct ReportArgs {
  std::vector<std::string> inputs;
  std::string out;
  std::string title = "locbench report";
};

nlohmann::json parse_file(const std::filesystem::path& path) { return read_json_file(path, "report (JSON)"); }

reports::Report load(const std::filesystem::path& path, const nlohmann::json& j) {
  const std::string schema = j.is_object() ? j.value("schema", "") : "";
  if (schema == reports::kShardSchema) {
    throw InputError(path.string(), 0, "a shard report: combine the shards with `locbench merge` first");
  }
  if (const auto errors = reports::validate_report_json(j); !errors.empty()) {
    throw InputError(path.string(), 0, "not a valid locbench report: " + errors.front());
  }
  return reports::report_from_json(j, path.string());
}

// Files as given (each must be a report); folders contribute every report below them, in
// the experiments' order, and say on stderr which other JSON files they skipped.
std::vector<reports::Report> load_all(const std::vector<std::string>& inputs) {
  std::vector<reports::Report> out;
  for (const std::string& in : inputs) {
    const std::filesystem::path p(in);
    if (!std::filesystem::is_directory(p)) {
      out.push_back(load(p, parse_file(p)));
      continue;
    }
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(p)) {
      if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    std::vector<reports::Report> here;
    for (const auto& f : files) {
      const nlohmann::json j = parse_file(f);
      if (!j.is_object() || j.value("schema", "") != reports::kReportSchema) {
        std::cerr << "locbench report: skipping " << f.string() << " (not a locbench report)\n";
        continue;
      }
      here.push_back(load(f, j));
    }
    if (here.empty()) throw InputError(in, 0, "folder holds no locbench reports");
    // A folder of two runs (one killed over an older folder's reports) is rendered, but said.
    std::set<std::string> run_ids;
    for (const auto& r : here) run_ids.insert(r.provenance.run_id.empty() ? "(none)" : r.provenance.run_id);
    if (run_ids.size() > 1) {
      std::cerr << "locbench report: warning: " << in << " mixes the reports of " << run_ids.size() << " runs (run ids";
      for (const std::string& id : run_ids) std::cerr << ' ' << id;
      std::cerr << "): `locbench gate` refuses such a folder\n";
    }
    // A folder's reports in the order `locbench list` shows the experiments.
    const auto rank = [](const reports::Report& r) {
      const auto& all = experiments::all_experiments();
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i]->name() == r.body.experiment) return i;
      }
      return all.size();
    };
    std::stable_sort(here.begin(), here.end(),
                     [&](const reports::Report& a, const reports::Report& b) { return rank(a) < rank(b); });
    for (auto& r : here) out.push_back(std::move(r));
  }
  return out;
}

int report(const ReportArgs& args) {
  check_outputs(args.inputs, {{"-o", args.out}}, ".json");
  const auto gnuplot = reports::find_gnuplot();
  if (!gnuplot) {
    throw UsageError(
        "gnuplot not found (looked for $LOCBENCH_GNUPLOT, then `gnuplot` on $PATH): the charts "
        "are drawn with it — install Debian's gnuplot-nox (scripts/setup.sh does)");
  }
  const std::vector<reports::Report> loaded = load_all(args.inputs);
  reports::HtmlOptions options;
  options.title = args.title;
  const std::string html = reports::html_report(loaded, reports::gnuplot_batch_renderer(*gnuplot), options);
  const std::filesystem::path out(args.out);
  write_file_atomically(out, html);
  std::cerr << "wrote " << out.string() << " (" << loaded.size() << " reports, " << html.size() << " bytes)\n";
  return kExitOk;
}

}  // namespace

Action add_report_command(CLI::App& app) {
  const auto [cmd, args] =
      add_verb<ReportArgs>(app, "report", "Write one self-contained HTML page (tables and charts) from reports");
  cmd->add_option("reports", args->inputs, "Report files, or folders holding them")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("-o,--out", args->out, "HTML file to write")->required();
  cmd->add_option("--title", args->title, "Page title")->capture_default_str();
  return [args = args] { return report(*args); };
}

}  // namespace locbench::cli
