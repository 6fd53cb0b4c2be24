#include "reports/gate_input.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.h"
#include "core/json_file.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"

namespace locbench::reports {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

double to_ns(double t, const std::string& unit, const std::string& file) {
  if (unit == "ns") return t;
  if (unit == "us") return t * 1e3;
  if (unit == "ms") return t * 1e6;
  if (unit == "s") return t * 1e9;
  throw InputError(file, 0, "benchmark time_unit \"" + unit + "\": expected ns, us, ms or s");
}

void add_benchmarks(const json& j, const std::string& file, GateInput& in) {
  std::map<std::string, std::vector<double>> iterations;
  std::map<std::string, double> means;
  for (const json& b : j.at("benchmarks")) {
    if (!b.is_object() || !b.contains("name") || !b.contains("real_time")) continue;  // BigO/RMS
    const std::string name = b.value("run_name", b.at("name").get<std::string>());
    // A benchmark that skipped (SkipWithError: its data are absent) measured nothing; leaving it
    // out makes every ratio that needs it "missing", which fails the gate.
    if (b.value("error_occurred", false)) continue;
    const std::string unit = b.value("time_unit", "ns");
    if (!b.at("real_time").is_number()) {
      throw InputError(file, 0, "benchmark " + name + ": real_time is not a number");
    }
    const double t = to_ns(b.at("real_time").get<double>(), unit, file);
    if (b.value("run_type", "iteration") == "aggregate") {
      if (b.value("aggregate_name", "") == "mean") means[name] = t;
    } else {
      iterations[name].push_back(t);
    }
  }
  for (const auto& [name, mean] : means) {
    if (!iterations.count(name)) iterations[name] = {mean};
  }
  for (auto& [name, samples] : iterations) {
    GateSeries s;
    s.key = "bench:" + name;
    s.variant = name;
    s.file = file;
    s.unit = "ns";
    s.is_time = true;
    std::vector<double> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    s.value = sorted[sorted.size() / 2];
    if (sorted.size() % 2 == 0) s.value = 0.5 * (sorted[sorted.size() / 2 - 1] + s.value);
    s.n = samples.size();
    s.samples = std::move(samples);
    in.series[s.key] = std::move(s);
  }
}

// The base seed from the command line that made the report: `run --seed N` (default 1).
std::string base_seed(const Provenance& p) {
  std::istringstream words(p.command_line);
  std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
  bool is_run = false;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] == "run") is_run = true;
    if (w[i] == "--seed" && i + 1 < w.size()) return w[i + 1];
    if (w[i].rfind("--seed=", 0) == 0) return w[i].substr(7);
  }
  return is_run ? "1" : "";
}

void add_report(const json& j, const std::string& file, GateInput& in) {
  if (const auto errors = validate_report_json(j); !errors.empty()) {
    throw InputError(file, 0, "not a valid locbench report: " + errors.front());
  }
  const Report r = report_from_json(j, file);
  in.revision_of[file] = r.provenance.git_revision;
  in.run_id_of[file] = r.provenance.run_id;
  if (!r.body.seeds.empty()) in.seed_of[file] = base_seed(r.provenance);
  for (const CaseNote& c : r.body.cases) {
    if (c.status == "skipped") in.skipped[r.body.experiment][c.name.substr(c.name.rfind('/') + 1)] = c.reason;
  }
  for (const DatasetRef& d : r.body.datasets) in.dataset_paths[r.body.experiment][d.name] = d.path;
  for (const MetricResult& m : r.body.results) {
    GateSeries s;
    s.key = r.body.experiment + ":" + m.name();
    s.experiment = r.body.experiment;
    s.dataset = m.dataset;
    s.variant = m.variant;
    s.file = file;
    s.unit = m.unit;
    s.better = m.better;
    s.value = m.summary.mean;
    s.n = m.summary.n;
    s.ci95_low = m.summary.ci95_low;
    s.ci95_high = m.summary.ci95_high;
    s.samples = m.values;
    s.min = m.summary.min;
    s.max = m.summary.max;
    if (in.series.count(s.key)) throw InputError(file, 0, "result " + s.key + " appears twice");
    in.series[s.key] = std::move(s);
  }
}

void add_file(const fs::path& path, GateInput& in) {
  const json j = read_json_file(path, "report (JSON)");
  in.sources.push_back(path.string());
  if (j.is_object() && j.contains("benchmarks") && j.at("benchmarks").is_array()) {
    try {
      add_benchmarks(j, path.string(), in);
    } catch (const json::exception& e) {
      throw InputError(path.string(), 0, std::string("Google Benchmark JSON: ") + e.what());
    }
  } else if (j.is_object() && j.contains("schema") && j.at("schema").is_string() &&
             j.at("schema").get<std::string>().rfind("locbench.gate/", 0) == 0) {
    in.sources.pop_back();  // a gate verdict lying among the reports: not an input
  } else if (j.is_object() && j.contains("schema")) {
    add_report(j, path.string(), in);
  } else {
    throw InputError(path.string(), 0,
                     "expected a locbench report (\"schema\") or Google Benchmark JSON "
                     "(\"benchmarks\")");
  }
}

}  // namespace

void require_one_run(const GateInput& in, bool revisions, const std::string& role) {
  const auto one = [&](const std::map<std::string, std::string>& of, const std::string& what) {
    const std::pair<const std::string, std::string>* first = nullptr;
    for (const auto& entry : of) {
      if (entry.second.empty()) continue;
      if (!first) {
        first = &entry;
      } else if (entry.second != first->second) {
        throw InputError(entry.first, 0,
                         "the " + role + " reports mix runs: " + what + " " + entry.second + " here, " + first->second +
                             " in " + first->first +
                             " (two runs into one folder?); pass --allow-mixed to compare them anyway");
      }
    }
  };
  one(in.seed_of, "base seed");
  if (revisions) one(in.revision_of, "git revision");
}

GateInput load_gate_input(const std::vector<std::string>& paths) {
  GateInput in;
  for (const std::string& p : paths) {
    if (fs::is_directory(p)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::recursive_directory_iterator(p)) {
        if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
      if (files.empty()) throw InputError(p, 0, "folder holds no .json report");
      for (const auto& f : files) add_file(f, in);
    } else if (fs::exists(p)) {
      add_file(p, in);
    } else {
      throw InputError(p, 0, "no such file or folder");
    }
  }
  return in;
}

}  // namespace locbench::reports
