#include "reports/html_report.h"

#include <fmt/format.h>

#include <cmath>

#include "reports/charts.h"
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
)css";

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
        html_escape(m.variant), html_escape(m.method), html_escape(m.dataset),
        with_unit(mean, m.unit), num(s.ci95_low), num(s.ci95_high), s.n, html_escape(m.over),
        html_escape(m.better),
        m.identifiable && !*m.identifiable ? " <span class=bad>not identifiable</span>" : "");
  }
  if (rows.empty()) return;
  h += "<h3>Results</h3>\n<table class=results><thead><tr><th>metric</th><th>method</th>"
       "<th>dataset</th><th>mean ± 95% interval</th><th>95% interval</th><th>n</th>"
       "<th>over</th><th>better</th></tr></thead><tbody>\n" +
       rows + "</tbody></table>\n";
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
        html_escape(m.variant), html_escape(m.method), html_escape(m.dataset),
        with_unit(num(s.mean), m.unit),
        identifiable ? "[" + num(s.ci95_low) + ", " + num(s.ci95_high) + "]" : "—",
        identifiable ? num(s.stddev) : "—",
        identifiable ? "yes" : "<span class=bad>not identifiable</span>", html_escape(m.note));
  }
  if (rows.empty()) return;
  h += "<h3>Estimates</h3>\n<table class=estimates><thead><tr><th>parameter</th><th>method</th>"
       "<th>dataset</th><th>estimate</th><th>95% interval</th><th>standard error</th>"
       "<th>identifiable</th><th>note</th></tr></thead><tbody>\n" +
       rows + "</tbody></table>\n";
}

void published_tables(std::string& h, const ExperimentResults& b) {
  for (const PublishedComparison& c : b.published) {
    h += fmt::format("<h3>Published vs ours: {} — {}{}</h3>\n", html_escape(c.source),
                     html_escape(c.quantity), c.unit.empty() ? "" : " [" + html_escape(c.unit) + "]");
    h += "<table class=published><thead><tr><th></th><th>published</th><th>ours</th>"
         "<th>ours − published</th><th>ours / published</th></tr></thead><tbody>\n";
    for (const PublishedRow& r : c.rows) {
      std::string diff = "—", ratio = "—";
      if (r.published && r.ours) {
        diff = num(*r.ours - *r.published);
        if (*r.published != 0.0) ratio = num(*r.ours / *r.published);
      }
      h += fmt::format("<tr><td>{}</td><td class=n>{}</td><td class=n>{}</td><td class=n>{}</td>"
                       "<td class=n>{}</td></tr>\n",
                       html_escape(r.label), num(r.published), num(r.ours), diff, ratio);
    }
    h += "</tbody></table>\n";
    if (!c.note.empty()) h += "<p class=note>" + html_escape(c.note) + "</p>\n";
  }
}

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

std::string html_report(const std::vector<Report>& reports, const ChartRenderer& render,
                        const HtmlOptions& options) {
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n"
       "<meta name=viewport content=\"width=device-width, initial-scale=1\">\n"
       "<link rel=icon href=\"data:,\">\n<title>" +
       html_escape(options.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  h += "<h1>" + html_escape(options.title) + "</h1>\n";
  h += "<table class=overview><thead><tr><th>experiment</th><th>results</th><th>published "
       "tables</th><th>Monte-Carlo runs</th><th>cases not run</th></tr></thead><tbody>\n";
  for (const Report& r : reports) {
    h += fmt::format("<tr><td><a href=\"#{}\">{}</a></td><td class=n>{}</td><td class=n>{}</td>"
                     "<td class=n>{}</td><td class=n>{}</td></tr>\n",
                     anchor(r.body.experiment), html_escape(r.body.experiment),
                     r.body.results.size(), r.body.published.size(), r.body.seeds.size(),
                     r.body.cases.size());
  }
  h += "</tbody></table>\n";
  int chart = 0;
  for (const Report& r : reports) {
    const ExperimentResults& b = r.body;
    const Provenance& p = r.provenance;
    h += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n<p>{}</p>\n", anchor(b.experiment),
                     html_escape(b.experiment), html_escape(b.description));
    h += fmt::format(
        "<p class=meta>locbench {} at {} ({}), {} · {} · {} seeds{}{}</p>\n",
        html_escape(p.tool_version), html_escape(p.git_revision), html_escape(p.build_type),
        html_escape(p.host), html_escape(p.utc_time), b.seeds.size(),
        p.threads ? fmt::format(" · {} threads", *p.threads) : "",
        p.shards ? fmt::format(" · merged from {} shards", *p.shards) : "");
    if (!b.datasets.empty()) {
      h += "<p class=meta>Data: ";
      for (std::size_t i = 0; i < b.datasets.size(); ++i) {
        const DatasetRef& d = b.datasets[i];
        h += (i ? "; " : "") + html_escape(d.name) +
             fmt::format(" ({}, {} records, {} s, {})", html_escape(d.path), d.records,
                         num(d.duration_s), html_escape(d.checksum));
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
        h += render(plot, id);
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
        h += fmt::format("<li><b>{}</b> ({}): {}</li>\n", html_escape(c.name),
                         html_escape(c.status), html_escape(c.reason));
      }
      h += "</ul>\n";
    }
    h += "</section>\n";
  }
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace locbench::reports
