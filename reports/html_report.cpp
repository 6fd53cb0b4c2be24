#include "reports/html_report.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <map>
#include <optional>

#include "reports/charts.h"
#include "reports/findings.h"
#include "reports/gnuplot_svg.h"

namespace locbench::reports {
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "—" : (v > 0 ? "∞" : "−∞");
  return fmt::format("{:.4g}", v);
}
std::string num(const std::optional<double>& v) { return v ? num(*v) : "—"; }

std::string anchor(const std::string& name) {
  std::string a = "exp-";
  for (char c : name) a += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return a;
}

std::string with_unit(const std::string& value, const std::string& unit) {
  return unit.empty() ? value : value + " " + html_escape(unit);
}

constexpr const char* kStyle = R"css(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:2rem auto;max-width:1100px;padding:0 1rem;color:#222;line-height:1.45}
h1{border-bottom:2px solid #333;padding-bottom:.3rem}
h2{margin-top:2.5rem;border-bottom:1px solid #bbb;padding-bottom:.2rem}
h3{margin-top:1.6rem}
table{border-collapse:collapse;margin:.6rem 0 1rem;font-size:.9rem}
th,td{border:1px solid #ccc;padding:.25rem .5rem;text-align:left;vertical-align:top}
th{background:#f2f2f2}
td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.meta{color:#555;font-size:.85rem}
.note{color:#444;font-size:.9rem;max-width:60rem}
.bad{color:#a40000;font-weight:600}
figure.chart{margin:1rem 0 2rem}
figure.chart svg{width:100%;max-width:760px;height:auto;border:1px solid #eee}
figcaption{font-size:.85rem;color:#555}
ul.findings li{margin-bottom:.4rem}
section#findings{background:#fafaf5;border:1px solid #ddd;padding:.2rem 1rem 1rem;margin:1rem 0 2rem}
td.v-reproduced{color:#116611;font-weight:600}
td.v-not-reproduced{color:#a40000;font-weight:600}
td.v-the-thesis-is-wrong{color:#8a5a00;font-weight:600}
)css";

// A titled table: a header row of `columns` above `rows`; nothing at all when there are no rows.
void titled_table(std::string& h, const char* title, const char* css_class, std::initializer_list<const char*> columns,
                  const std::string& rows) {
  if (rows.empty()) return;
  h += fmt::format("<h3>{}</h3>\n<table class={}><thead><tr>", title, css_class);
  for (const char* c : columns) h += fmt::format("<th>{}</th>", c);
  h += "</tr></thead><tbody>\n" + rows + "</tbody></table>\n";
}

void summary_table(std::string& h, const ExperimentResults& b) {
  std::string rows;
  for (const MetricResult& m : b.results) {
    if (m.over == "estimate") continue;
    const Summary& s = m.summary;
    const double half = (s.ci95_high - s.ci95_low) / 2.0;
    const std::string mean = s.n > 1 ? num(s.mean) + " ± " + num(half) : num(s.mean);
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td class=n>{}</td><td class=n>[{}, {}]</td>"
        "<td class=n>{}</td><td>{}</td><td>{}{}</td></tr>\n",
        html_escape(m.variant), html_escape(m.method), html_escape(m.dataset), with_unit(mean, m.unit), num(s.ci95_low),
        num(s.ci95_high), s.n, html_escape(m.over), html_escape(m.better),
        m.identifiable && !*m.identifiable ? " <span class=bad>not identifiable</span>" : "");
  }
  titled_table(h, "Results", "results",
               {"metric", "method", "dataset", "mean ± 95% interval", "95% interval", "n", "over", "better"}, rows);
}

void estimates_table(std::string& h, const ExperimentResults& b) {
  std::string rows;
  for (const MetricResult& m : b.results) {
    if (m.over != "estimate") continue;
    const Summary& s = m.summary;
    const bool identifiable = !m.identifiable || *m.identifiable;
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td class=n>{}</td><td class=n>{}</td>"
        "<td class=n>{}</td><td>{}</td><td class=note>{}</td></tr>\n",
        html_escape(m.variant), html_escape(m.method), html_escape(m.dataset), with_unit(num(s.mean), m.unit),
        identifiable ? "[" + num(s.ci95_low) + ", " + num(s.ci95_high) + "]" : "—", identifiable ? num(s.stddev) : "—",
        identifiable ? "yes" : "<span class=bad>not identifiable</span>", html_escape(m.note));
  }
  titled_table(h, "Estimates", "estimates",
               {"parameter", "method", "dataset", "estimate", "95% interval", "standard error", "identifiable", "note"},
               rows);
}

void published_tables(std::string& h, const ExperimentResults& b) {
  for (const PublishedComparison& c : b.published) {
    h += fmt::format("<h3>Published vs ours: {} — {}{}</h3>\n", html_escape(c.source), html_escape(c.quantity),
                     c.unit.empty() ? "" : " [" + html_escape(c.unit) + "]");
    h += "<table class=published><thead><tr><th></th><th>published</th><th>ours</th>"
         "<th>ours − published</th><th>ours / published</th></tr></thead><tbody>\n";
    for (const PublishedRow& r : c.rows) {
      std::string diff = "—", ratio = "—";
      if (r.published && r.ours) {
        diff = num(*r.ours - *r.published);
        if (*r.published != 0.0) ratio = num(*r.ours / *r.published);
      }
      h += fmt::format(
          "<tr><td>{}</td><td class=n>{}</td><td class=n>{}</td><td class=n>{}</td>"
          "<td class=n>{}</td></tr>\n",
          html_escape(r.label), num(r.published), num(r.ours), diff, ratio);
    }
    h += "</tbody></table>\n";
    if (!c.note.empty()) h += "<p class=note>" + html_escape(c.note) + "</p>\n";
  }
}

std::string verdict_class(Verdict v) {
  std::string c = "v-";
  for (char ch : to_string(v)) c += ch == ' ' ? '-' : ch;
  return c;
}

// Our measurement of a table in one cell: each row's published → ours, in the table's unit.
std::string measurement_cell(const PublishedComparison& c) {
  std::string out;
  for (const PublishedRow& r : c.rows) {
    if (!r.published || !r.ours) continue;
    out += fmt::format("{}{}: {} → {}", out.empty() ? "" : "; ", html_escape(r.label), num(r.published), num(r.ours));
  }
  return out.empty() ? "—" : with_unit(out, c.unit) + " <span class=meta>(published → ours)</span>";
}

std::string gain_text(const KeptCause& c) {
  if (!c.gain) return "—";
  const FindingGain& g = *c.gain;
  const double rel = g.before != 0.0 ? (g.before - g.after) / std::abs(g.before) : 0.0;
  return fmt::format("{} {} → {} ({:+.1f}%)", html_escape(g.metric), num(g.before), num(g.after), 100.0 * rel);
}

// Rows of the twins' predictivity: the results an experiment reports under methods "nominal_twin"
// and "extended_twin" on dataset "all_logs" (pipelines/predictivity_report.h),
// one row per metric.
std::string twin_rows(const std::vector<Report>& reports) {
  std::string rows;
  for (const Report& r : reports) {
    // metric → statistic → {nominal, extended}; for the extended twin's misses split by the sensor
    // twin, {the motion model's, the sensor model's}
    std::map<std::string, std::map<std::string, std::pair<std::optional<double>, std::optional<double>>>> by_metric;
    for (const MetricResult& m : r.body.results) {
      if (m.dataset != "all_logs" || (m.method != "nominal_twin" && m.method != "extended_twin")) continue;
      for (const char* statistic : {"_covered_fraction", "_pearson_r", "_mmrv"}) {
        if (!m.variant.ends_with(statistic)) continue;
        auto& pair = by_metric[m.variant.substr(0, m.variant.size() - std::strlen(statistic))][statistic];
        (m.method == "nominal_twin" ? pair.first : pair.second) = m.summary.mean;
      }
      for (const auto& [model, motion] :
           {std::pair{"_misses_of_the_motion_model", true}, std::pair{"_misses_of_the_sensor_model", false}}) {
        if (m.method != "extended_twin" || !m.variant.ends_with(model)) continue;
        auto& pair = by_metric[m.variant.substr(0, m.variant.size() - std::strlen(model))]["_misses"];
        (motion ? pair.first : pair.second) = m.summary.mean;
      }
    }
    for (const auto& [metric, stats] : by_metric) {
      const auto cell = [&, &stats = stats](const char* statistic, bool percent) {
        const auto it = stats.find(statistic);
        if (it == stats.end()) return std::string("—");
        const auto show = [&](const std::optional<double>& v) {
          return !v ? std::string("—") : percent ? fmt::format("{:.0f}%", 100.0 * *v) : num(*v);
        };
        return show(it->second.first) + " / " + show(it->second.second);
      };
      rows += fmt::format(
          "<tr><td><a href=\"#{}\">{}</a></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
          anchor(r.body.experiment), html_escape(r.body.experiment), html_escape(metric),
          cell("_covered_fraction", true), cell("_pearson_r", false), cell("_mmrv", false), cell("_misses", false));
    }
  }
  return rows;
}

// The front section: published tables with a verdict, then the diagnosed logs.
void findings_section(std::string& h, const std::vector<Report>& reports) {
  std::string tables, logs;
  for (const Report& r : reports) {
    for (const PublishedComparison& c : r.body.published) {
      const TableFinding f = table_finding(c);
      if (f.verdict == Verdict::kNoVerdict) continue;
      tables += fmt::format(
          "<tr><td><a href=\"#{}\">{}</a></td><td>{} — {}{}</td><td>{}</td><td class=\"{}\">{}</td><td>{}</td></tr>\n",
          anchor(r.body.experiment), html_escape(r.body.experiment), html_escape(c.source), html_escape(c.quantity),
          c.claim.empty() ? "" : "<br>" + html_escape(c.claim), measurement_cell(c), verdict_class(f.verdict),
          to_string(f.verdict), html_escape(f.reason));
    }
    for (const DiagnosedLog& d : r.body.diagnoses) {
      std::string causes;
      for (const KeptCause& c : d.causes) {
        std::string params;
        for (const FindingEstimate& e : c.parameters) {
          params += fmt::format("{}{} = {} [{}, {}]", params.empty() ? "" : ", ", html_escape(e.name), num(e.value),
                                num(e.lo), num(e.hi));
        }
        causes += fmt::format("<li><b>{}</b>{}: {}; held-out {}</li>", html_escape(c.id),
                              c.identifiable ? "" : " <span class=bad>confounded</span>", params.empty() ? "—" : params,
                              gain_text(c));
      }
      logs += fmt::format("<tr><td><a href=\"#{}\">{}</a></td><td>{}</td><td>{}</td><td class=note>{}</td></tr>\n",
                          anchor(r.body.experiment), html_escape(d.log), html_escape(d.reference),
                          causes.empty() ? "none kept" : "<ul>" + causes + "</ul>", html_escape(d.verdict));
    }
  }
  const std::string twins = twin_rows(reports);
  if (tables.empty() && logs.empty() && twins.empty()) return;
  h += "<section id=findings>\n<h2>Findings</h2>\n";
  if (!tables.empty()) {
    h += "<h3>Published tables: the thesis's claim, our measurement, the verdict</h3>\n"
         "<p class=note>The verdict is computed from the numbers below: a row is reproduced when |ours − "
         "published| is within the tolerance its experiment states; the thesis is wrong when our figure is "
         "confirmed by an independent computation and the published one is not.</p>\n"
         "<table class=findings-published><thead><tr><th>experiment</th><th>claim</th><th>measured</th>"
         "<th>verdict</th><th>reason</th></tr></thead><tbody>\n" +
         tables + "</tbody></table>\n";
  }
  if (!logs.empty()) {
    h += "<h3>Real logs: what the diagnosis kept</h3>\n"
         "<p class=note>Causes kept by the diagnosis, each parameter with its 95% interval, and the held-out "
         "gain of the cause alone in its primary metric (before → after).</p>\n"
         "<table class=findings-diagnosis><thead><tr><th>log</th><th>reference</th><th>causes kept</th>"
         "<th>verdict</th></tr></thead><tbody>\n" +
         logs + "</tbody></table>\n";
  }
  if (!twins.empty()) {
    h += "<h3>Twins: does the simulator forecast the real result?</h3>\n"
         "<p class=note>Per metric across methods × logs: the share of real values inside each twin's 95% "
         "predictive interval, Pearson r of its prediction against the real value and the mean maximum rank "
         "violation of the methods (MMRV, lower is better) — nominal twin / extended twin (the diagnosed "
         "model); and the extended twin's misses that a sensor twin (the log's own motion, the fitted sensor) "
         "covers, the motion model's, / those it misses too, the sensor model's.</p>\n"
         "<table class=findings-twins><thead><tr><th>experiment</th><th>metric</th><th>covered</th><th>Pearson "
         "r</th><th>MMRV</th><th>misses: motion / sensor model</th></tr></thead><tbody>\n" +
         twins + "</tbody></table>\n";
  }
  h += "</section>\n";
}

// Stands for chart i in the page until the charts are drawn (all at once).
std::string chart_placeholder(std::size_t i) { return fmt::format("\x01chart{}\x01", i); }

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      case '\x01': break;  // reserved for the page's chart placeholders
      default: out += c;
    }
  }
  return out;
}

ChartRenderer gnuplot_renderer(std::filesystem::path gnuplot) {
  return [gnuplot](const Plot& plot, const std::string& id) {
    return inline_svg(run_gnuplot(gnuplot, plot_script(plot)), id + "-");
  };
}

ChartBatchRenderer gnuplot_batch_renderer(std::filesystem::path gnuplot) {
  return [gnuplot](const std::vector<Plot>& plots, const std::vector<std::string>& ids) {
    std::vector<std::string> scripts;
    scripts.reserve(plots.size());
    for (const Plot& p : plots) scripts.push_back(plot_script(p));
    std::vector<std::string> svgs = run_gnuplot_batch(gnuplot, scripts);
    for (std::size_t i = 0; i < svgs.size(); ++i) svgs[i] = inline_svg(svgs[i], ids[i] + "-");
    return svgs;
  };
}

std::string html_report(const std::vector<Report>& reports, const ChartRenderer& render, const HtmlOptions& options) {
  return html_report(
      reports,
      [&render](const std::vector<Plot>& plots, const std::vector<std::string>& ids) {
        std::vector<std::string> out;
        for (std::size_t i = 0; i < plots.size(); ++i) out.push_back(render(plots[i], ids[i]));
        return out;
      },
      options);
}

std::string html_report(const std::vector<Report>& reports, const ChartBatchRenderer& render,
                        const HtmlOptions& options) {
  std::vector<Plot> chart_plots;
  std::vector<std::string> chart_ids;
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n"
       "<meta name=viewport content=\"width=device-width, initial-scale=1\">\n"
       "<link rel=icon href=\"data:,\">\n<title>" +
       html_escape(options.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  h += "<h1>" + html_escape(options.title) + "</h1>\n";
  findings_section(h, reports);
  h += "<h2 id=index>Experiments</h2>\n<table "
       "class=overview><thead><tr><th>experiment</th><th>results</th><th>published "
       "tables</th><th>Monte-Carlo runs</th><th>cases not run</th></tr></thead><tbody>\n";
  for (const Report& r : reports) {
    h += fmt::format(
        "<tr><td><a href=\"#{}\">{}</a></td><td class=n>{}</td><td class=n>{}</td>"
        "<td class=n>{}</td><td class=n>{}</td></tr>\n",
        anchor(r.body.experiment), html_escape(r.body.experiment), r.body.results.size(), r.body.published.size(),
        r.body.seeds.size(), r.body.cases.size());
  }
  h += "</tbody></table>\n";
  int chart = 0;
  for (const Report& r : reports) {
    const ExperimentResults& b = r.body;
    const Provenance& p = r.provenance;
    h += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n<p>{}</p>\n", anchor(b.experiment), html_escape(b.experiment),
                     html_escape(b.description));
    h += fmt::format("<p class=meta>locbench {} at {} ({}), {} · {} · {} seeds{}{}</p>\n", html_escape(p.tool_version),
                     html_escape(p.git_revision), html_escape(p.build_type), html_escape(p.host),
                     html_escape(p.utc_time), b.seeds.size(), p.threads ? fmt::format(" · {} threads", *p.threads) : "",
                     p.shards ? fmt::format(" · merged from {} shards", *p.shards) : "");
    if (!b.datasets.empty()) {
      h += "<p class=meta>Data: ";
      for (std::size_t i = 0; i < b.datasets.size(); ++i) {
        const DatasetRef& d = b.datasets[i];
        h += (i ? "; " : "") + html_escape(d.name) +
             fmt::format(" ({}, {} records, {} s, {})", html_escape(d.path), d.records, num(d.duration_s),
                         html_escape(d.checksum));
      }
      h += "</p>\n";
    }
    summary_table(h, b);
    estimates_table(h, b);
    published_tables(h, b);
    // Charts, then the scan pairs drawn (laser/real_logs' worst relations) under their own heading.
    std::vector<Plot> plots, scan_pairs;
    for (const Plot& each : b.plots) (each.kind == "scan_pair" ? scan_pairs : plots).push_back(each);
    for (Plot& hp : metric_histograms(b)) plots.push_back(std::move(hp));
    const auto figures = [&](const std::vector<Plot>& ps, const char* heading) {
      if (!ps.empty()) h += fmt::format("<h3>{}</h3>\n", heading);
      for (const Plot& plot : ps) {
        const std::string id = fmt::format("chart{}", ++chart);
        h += fmt::format("<figure class=chart id=\"{}\" data-kind=\"{}\">\n", id, html_escape(plot.kind));
        h += chart_placeholder(chart_plots.size());
        chart_plots.push_back(plot);
        chart_ids.push_back(id);
        h += fmt::format("\n<figcaption>{}{}</figcaption>\n</figure>\n", html_escape(plot.title),
                         plot.note.empty() ? "" : " — " + html_escape(plot.note));
      }
    };
    figures(plots, "Charts");
    figures(scan_pairs, "Scan pairs drawn: both scans, lines and matches, before and after");
    if (!b.notes.empty()) {
      h += "<h3>Findings</h3>\n<ul class=findings>\n";
      for (const std::string& n : b.notes) h += "<li>" + html_escape(n) + "</li>\n";
      h += "</ul>\n";
    }
    if (!b.cases.empty()) {
      h += "<h3>Cases not run</h3>\n<ul>\n";
      for (const CaseNote& c : b.cases) {
        h += fmt::format("<li><b>{}</b> ({}): {}</li>\n", html_escape(c.name), html_escape(c.status),
                         html_escape(c.reason));
      }
      h += "</ul>\n";
    }
    h += "</section>\n";
  }
  h += "</body>\n</html>\n";
  // The charts, drawn together, in place of their placeholders (in page order).
  const std::vector<std::string> svgs =
      chart_plots.empty() ? std::vector<std::string>{} : render(chart_plots, chart_ids);
  std::string page;
  page.reserve(h.size() + 64 * 1024 * svgs.size());
  std::size_t from = 0;
  for (std::size_t i = 0; i < chart_plots.size(); ++i) {
    const std::string mark = chart_placeholder(i);
    const std::size_t at = h.find(mark, from);
    page.append(h, from, at - from);
    page += i < svgs.size() ? svgs[i] : std::string();
    from = at + mark.size();
  }
  page.append(h, from, std::string::npos);
  return page;
}

}  // namespace locbench::reports
