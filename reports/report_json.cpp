#include "reports/report_json.h"

#include "core/output_file.h"

#include <cmath>
#include <fstream>

#include "core/errors.h"
#include "core/json_file.h"

namespace locbench::reports {
namespace {
using nlohmann::json;

json optional_number(const std::optional<double>& v) { return v && std::isfinite(*v) ? json(*v) : json(nullptr); }

json metric_to_json(const MetricResult& m) {
  const Summary& s = m.summary;
  json j = {{"name", m.name()},
            {"method", m.method},
            {"dataset", m.dataset},
            {"variant", m.variant},
            {"unit", m.unit},
            {"better", m.better},
            {"over", m.over},
            {"n", s.n},
            {"mean", s.mean},
            {"stddev", s.stddev},
            {"ci95", {s.ci95_low, s.ci95_high}},
            {"median", s.median},
            {"min", s.min},
            {"max", s.max}};
  if (!m.values.empty()) j["values"] = m.values;
  if (m.identifiable) j["identifiable"] = *m.identifiable;
  if (!m.note.empty()) j["note"] = m.note;
  return j;
}

template <typename T>
T get(const json& j, const char* key, const std::string& source, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) {
    throw InputError(source, 0, where + ": missing field \"" + key + "\"");
  }
  try {
    return j.at(key).get<T>();
  } catch (const json::exception&) {
    throw InputError(source, 0, where + ": field \"" + key + "\" has the wrong type");
  }
}

json diagnosed_log_to_json(const DiagnosedLog& d) {
  json causes = json::array();
  for (const KeptCause& c : d.causes) {
    json params = json::array();
    for (const FindingEstimate& e : c.parameters) {
      params.push_back({{"name", e.name},
                        {"value", optional_number(e.value)},
                        {"lo", optional_number(e.lo)},
                        {"hi", optional_number(e.hi)}});
    }
    json cj = {{"id", c.id}, {"parameters", params}, {"identifiable", c.identifiable}};
    if (c.gain) {
      cj["gain"] = {{"metric", c.gain->metric},
                    {"before", optional_number(c.gain->before)},
                    {"after", optional_number(c.gain->after)}};
    }
    causes.push_back(std::move(cj));
  }
  return {{"log", d.log}, {"reference", d.reference}, {"causes", causes}, {"verdict", d.verdict}};
}

double number_or_nan(const json& j, const char* key, const std::string& source, const std::string& where) {
  if (j.contains(key) && j.at(key).is_null()) return std::nan("");
  return get<double>(j, key, source, where);
}

DiagnosedLog diagnosed_log_from_json(const json& j, const std::string& source) {
  DiagnosedLog d;
  d.log = get<std::string>(j, "log", source, "diagnoses");
  d.reference = get<std::string>(j, "reference", source, "diagnoses");
  d.verdict = get<std::string>(j, "verdict", source, "diagnoses");
  for (const json& cj : get<json>(j, "causes", source, "diagnoses")) {
    KeptCause c;
    c.id = get<std::string>(cj, "id", source, "diagnoses cause");
    c.identifiable = get<bool>(cj, "identifiable", source, "diagnoses cause");
    for (const json& e : get<json>(cj, "parameters", source, "diagnoses cause")) {
      c.parameters.push_back(
          {get<std::string>(e, "name", source, "cause parameter"), number_or_nan(e, "value", source, "cause parameter"),
           number_or_nan(e, "lo", source, "cause parameter"), number_or_nan(e, "hi", source, "cause parameter")});
    }
    if (cj.contains("gain")) {
      const json& g = cj.at("gain");
      c.gain = FindingGain{get<std::string>(g, "metric", source, "cause gain"),
                           number_or_nan(g, "before", source, "cause gain"),
                           number_or_nan(g, "after", source, "cause gain")};
    }
    d.causes.push_back(std::move(c));
  }
  return d;
}

json plot_to_json(const Plot& p) {
  json series = json::array();
  for (const PlotSeries& s : p.series) {
    series.push_back({{"name", s.name}, {"x", s.x}, {"y", s.y}});
  }
  return {{"name", p.name},
          {"kind", p.kind},
          {"title", p.title},
          {"x", {{"label", p.x_label}, {"unit", p.x_unit}}},
          {"y", {{"label", p.y_label}, {"unit", p.y_unit}}},
          {"series", series},
          {"note", p.note}};
}

Plot plot_from_json(const json& j, const std::string& source) {
  Plot p;
  p.name = get<std::string>(j, "name", source, "plot");
  p.kind = get<std::string>(j, "kind", source, "plot");
  p.title = get<std::string>(j, "title", source, "plot");
  const json x = get<json>(j, "x", source, "plot");
  const json y = get<json>(j, "y", source, "plot");
  p.x_label = get<std::string>(x, "label", source, "plot x");
  p.x_unit = get<std::string>(x, "unit", source, "plot x");
  p.y_label = get<std::string>(y, "label", source, "plot y");
  p.y_unit = get<std::string>(y, "unit", source, "plot y");
  if (j.contains("note")) p.note = get<std::string>(j, "note", source, "plot");
  for (const json& s : get<json>(j, "series", source, "plot")) {
    PlotSeries ps;
    ps.name = get<std::string>(s, "name", source, "plot series");
    ps.x = get<std::vector<double>>(s, "x", source, "plot series");
    ps.y = get<std::vector<double>>(s, "y", source, "plot series");
    if (p.kind != "histogram" && p.kind != "cdf" && ps.x.size() != ps.y.size()) {
      throw InputError(source, 0, "plot " + p.name + ", series " + ps.name + ": x and y differ in length");
    }
    p.series.push_back(std::move(ps));
  }
  return p;
}

}  // namespace

json results_to_json(const ExperimentResults& b) {
  json j;
  j["experiment"] = {{"name", b.experiment}, {"description", b.description}};
  j["seeds"] = b.seeds;
  j["datasets"] = json::array();
  for (const DatasetRef& d : b.datasets) {
    j["datasets"].push_back({{"name", d.name},
                             {"path", d.path},
                             {"checksum", d.checksum},
                             {"records", d.records},
                             {"duration_s", d.duration_s}});
  }
  j["configuration"] = b.configuration;
  j["results"] = json::array();
  for (const MetricResult& m : b.results) j["results"].push_back(metric_to_json(m));
  j["published"] = json::array();
  for (const PublishedComparison& c : b.published) {
    json rows = json::array();
    for (const PublishedRow& row : c.rows) {
      json r = {
          {"label", row.label}, {"published", optional_number(row.published)}, {"ours", optional_number(row.ours)}};
      if (row.check) r["check"] = optional_number(row.check);
      if (!row.compared) r["compared"] = false;
      if (row.tolerance) r["tolerance"] = *row.tolerance;
      rows.push_back(std::move(r));
    }
    json pc = {{"source", c.source}, {"quantity", c.quantity}, {"unit", c.unit}, {"rows", rows}, {"note", c.note}};
    if (!c.claim.empty()) pc["claim"] = c.claim;
    if (c.tolerance) pc["tolerance"] = *c.tolerance;
    if (c.relative_tolerance) pc["relative_tolerance"] = *c.relative_tolerance;
    if (!c.tolerance_basis.empty()) pc["tolerance_basis"] = c.tolerance_basis;
    j["published"].push_back(std::move(pc));
  }
  j["cases"] = json::array();
  for (const CaseNote& c : b.cases) {
    j["cases"].push_back({{"name", c.name}, {"status", c.status}, {"reason", c.reason}});
  }
  j["notes"] = b.notes;
  if (!b.plots.empty()) {
    j["plots"] = json::array();
    for (const Plot& p : b.plots) j["plots"].push_back(plot_to_json(p));
  }
  if (!b.diagnoses.empty()) {
    j["diagnoses"] = json::array();
    for (const DiagnosedLog& d : b.diagnoses) j["diagnoses"].push_back(diagnosed_log_to_json(d));
  }
  return j;
}

json to_json(const Report& r) {
  const Provenance& p = r.provenance;
  json j = results_to_json(r.body);
  j["schema"] = kReportSchema;
  j["context"] = {{"tool", "locbench"},
                  {"tool_version", p.tool_version},
                  {"git_revision", p.git_revision},
                  {"compiler", p.compiler},
                  {"compiler_flags", p.compiler_flags},
                  {"build_type", p.build_type},
                  {"host", p.host},
                  {"utc_time", p.utc_time},
                  {"command_line", p.command_line}};
  if (p.threads) j["context"]["threads"] = *p.threads;
  if (p.shards) j["context"]["shards"] = *p.shards;
  if (!p.run_id.empty()) j["context"]["run_id"] = p.run_id;
  return j;
}

Provenance provenance_from_json(const json& c, const std::string& source) {
  Provenance p;
  p.tool_version = get<std::string>(c, "tool_version", source, "context");
  p.git_revision = get<std::string>(c, "git_revision", source, "context");
  p.compiler = get<std::string>(c, "compiler", source, "context");
  p.compiler_flags = get<std::string>(c, "compiler_flags", source, "context");
  p.build_type = get<std::string>(c, "build_type", source, "context");
  p.host = get<std::string>(c, "host", source, "context");
  p.utc_time = get<std::string>(c, "utc_time", source, "context");
  p.command_line = get<std::string>(c, "command_line", source, "context");
  if (c.contains("threads")) p.threads = get<int>(c, "threads", source, "context");
  if (c.contains("shards")) p.shards = get<int>(c, "shards", source, "context");
  if (c.contains("run_id")) p.run_id = get<std::string>(c, "run_id", source, "context");
  return p;
}

json provenance_to_json(const Provenance& p) {
  Report r;
  r.provenance = p;
  return to_json(r).at("context");
}

ExperimentResults results_from_json(const json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, 0, "expected a JSON object (experiment results)");
  ExperimentResults b;
  const json& e = j.contains("experiment") ? j.at("experiment") : json::object();
  b.experiment = get<std::string>(e, "name", source, "experiment");
  b.description = get<std::string>(e, "description", source, "experiment");
  b.seeds = get<std::vector<std::uint64_t>>(j, "seeds", source, "report");
  for (const json& d : get<json>(j, "datasets", source, "report")) {
    b.datasets.push_back(
        {get<std::string>(d, "name", source, "dataset"), get<std::string>(d, "path", source, "dataset"),
         get<std::string>(d, "checksum", source, "dataset"), get<std::size_t>(d, "records", source, "dataset"),
         get<double>(d, "duration_s", source, "dataset")});
  }
  b.configuration = get<json>(j, "configuration", source, "report");
  for (const json& m : get<json>(j, "results", source, "report")) {
    MetricResult x;
    const std::string where = "result";
    x.method = get<std::string>(m, "method", source, where);
    x.dataset = get<std::string>(m, "dataset", source, where);
    x.variant = get<std::string>(m, "variant", source, where);
    x.unit = get<std::string>(m, "unit", source, where);
    x.better = get<std::string>(m, "better", source, where);
    x.over = get<std::string>(m, "over", source, where);
    x.summary.n = get<std::size_t>(m, "n", source, where);
    x.summary.mean = get<double>(m, "mean", source, where);
    x.summary.stddev = get<double>(m, "stddev", source, where);
    const auto ci = get<std::vector<double>>(m, "ci95", source, where);
    if (ci.size() != 2) throw InputError(source, 0, "result: ci95 must have 2 numbers");
    x.summary.ci95_low = ci[0];
    x.summary.ci95_high = ci[1];
    x.summary.median = get<double>(m, "median", source, where);
    x.summary.min = get<double>(m, "min", source, where);
    x.summary.max = get<double>(m, "max", source, where);
    if (m.contains("values")) x.values = get<std::vector<double>>(m, "values", source, where);
    if (m.contains("identifiable")) x.identifiable = get<bool>(m, "identifiable", source, where);
    if (m.contains("note")) x.note = get<std::string>(m, "note", source, where);
    b.results.push_back(std::move(x));
  }
  for (const json& pc : get<json>(j, "published", source, "report")) {
    PublishedComparison x;
    x.source = get<std::string>(pc, "source", source, "published");
    x.quantity = get<std::string>(pc, "quantity", source, "published");
    x.unit = get<std::string>(pc, "unit", source, "published");
    x.note = get<std::string>(pc, "note", source, "published");
    if (pc.contains("claim")) x.claim = get<std::string>(pc, "claim", source, "published");
    if (pc.contains("tolerance")) x.tolerance = get<double>(pc, "tolerance", source, "published");
    if (pc.contains("relative_tolerance")) {
      x.relative_tolerance = get<double>(pc, "relative_tolerance", source, "published");
    }
    if (pc.contains("tolerance_basis")) {
      x.tolerance_basis = get<std::string>(pc, "tolerance_basis", source, "published");
    }
    for (const json& row : get<json>(pc, "rows", source, "published")) {
      PublishedRow pr;
      pr.label = get<std::string>(row, "label", source, "published row");
      if (row.contains("published") && !row["published"].is_null()) {
        pr.published = get<double>(row, "published", source, "published row");
      }
      if (row.contains("ours") && !row["ours"].is_null()) {
        pr.ours = get<double>(row, "ours", source, "published row");
      }
      if (row.contains("check") && !row["check"].is_null()) {
        pr.check = get<double>(row, "check", source, "published row");
      }
      if (row.contains("compared")) pr.compared = get<bool>(row, "compared", source, "published row");
      if (row.contains("tolerance")) pr.tolerance = get<double>(row, "tolerance", source, "published row");
      x.rows.push_back(std::move(pr));
    }
    b.published.push_back(std::move(x));
  }
  for (const json& cn : get<json>(j, "cases", source, "report")) {
    b.cases.push_back({get<std::string>(cn, "name", source, "case"), get<std::string>(cn, "status", source, "case"),
                       get<std::string>(cn, "reason", source, "case")});
  }
  if (j.contains("notes")) b.notes = get<std::vector<std::string>>(j, "notes", source, "report");
  if (j.contains("plots")) {
    for (const json& p : get<json>(j, "plots", source, "report")) {
      b.plots.push_back(plot_from_json(p, source));
    }
  }
  if (j.contains("diagnoses")) {
    for (const json& d : get<json>(j, "diagnoses", source, "report")) {
      b.diagnoses.push_back(diagnosed_log_from_json(d, source));
    }
  }
  return b;
}

Report report_from_json(const json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(source, 0, "expected a JSON object (a locbench report)");
  const auto schema = get<std::string>(j, "schema", source, "report");
  if (schema != kReportSchema) {
    throw InputError(source, 0, "expected schema \"" + std::string(kReportSchema) + "\", found \"" + schema + "\"");
  }
  Report r;
  r.provenance = provenance_from_json(j.contains("context") ? j.at("context") : json::object(), source);
  r.body = results_from_json(j, source);
  return r;
}

std::filesystem::path write_report(const Report& report, const std::filesystem::path& path) {
  write_file_atomically(path, to_json(report).dump(2) + "\n");
  return path;
}

Report read_report(const std::filesystem::path& path) {
  return report_from_json(read_json_file(path, "report (JSON)"), path.string());
}

}  // namespace locbench::reports
