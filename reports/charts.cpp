#include "reports/charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace locbench::reports {
namespace {

// A gnuplot single-quoted string ('' stands for ').
std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

std::string axis_label(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " [" + unit + "]";
}

// A datablock $name of finite (x, y) rows.
std::string datablock(const std::string& name, const std::vector<double>& x, const std::vector<double>& y) {
  std::string out = "$" + name + " << EOD\n";
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) out += fmt::format("{:.9g} {:.9g}\n", x[i], y[i]);
  }
  return out + "EOD\n";
}

// Segments as consecutive (x, y) pairs, one blank line after each so that gnuplot does not join
// them; a pair with a non-finite coordinate is left out.
std::string segment_datablock(const std::string& name, const std::vector<double>& x, const std::vector<double>& y) {
  std::string out = "$" + name + " << EOD\n";
  for (std::size_t i = 0; i + 1 < std::min(x.size(), y.size()); i += 2) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(x[i + 1]) || !std::isfinite(y[i + 1])) {
      continue;
    }
    out += fmt::format("{:.9g} {:.9g}\n{:.9g} {:.9g}\n\n", x[i], y[i], x[i + 1], y[i + 1]);
  }
  return out + "EOD\n";
}

constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

}  // namespace

bool is_segment_series(const std::string& name) { return name.ends_with("lines") || name.ends_with("matches"); }

Histogram histogram(const std::vector<std::vector<double>>& samples, int bins) {
  Histogram h;
  bins = std::max(bins, 1);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : samples) {
    for (double v : s) {
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (!std::isfinite(lo)) lo = hi = 0.0;
  if (hi - lo <= 0.0) {
    const double pad = std::max(std::abs(lo), 1.0) * 1e-9;
    lo -= pad * bins / 2.0;
    hi = lo + pad * bins;
  }
  h.low = lo;
  h.width = (hi - lo) / bins;
  for (const auto& s : samples) {
    std::vector<int> c(static_cast<std::size_t>(bins), 0);
    for (double v : s) {
      if (!std::isfinite(v)) continue;
      const int b = std::clamp(static_cast<int>(std::floor((v - lo) / h.width)), 0, bins - 1);
      ++c[static_cast<std::size_t>(b)];
    }
    h.counts.push_back(std::move(c));
  }
  return h;
}

Plot sample_plot(std::string kind, std::string y_label, std::string name, std::string title, std::string x_label,
                 std::string x_unit, std::vector<PlotSeries> samples, std::string note) {
  return {std::move(name),    std::move(kind), std::move(title),   std::move(x_label), std::move(x_unit),
          std::move(y_label), std::string(),   std::move(samples), std::move(note)};
}

Plot histogram_plot(std::string name, std::string title, std::string x_label, std::string x_unit,
                    std::vector<PlotSeries> samples, std::string note) {
  return sample_plot("histogram", "runs", std::move(name), std::move(title), std::move(x_label), std::move(x_unit),
                     std::move(samples), std::move(note));
}

std::vector<Plot> metric_histograms(const ExperimentResults& results, std::size_t min_values, std::size_t max_plots) {
  // (dataset, variant) in first-seen order → methods' values.
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, std::vector<const MetricResult*>> groups;
  for (const MetricResult& m : results.results) {
    if (m.over != "monte_carlo_runs" || m.values.size() < min_values) continue;
    if (m.variant.find("error") == std::string::npos) continue;
    const auto key = std::make_pair(m.dataset, m.variant);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&m);
  }
  std::vector<Plot> plots;
  for (const auto& key : order) {
    if (plots.size() >= max_plots) break;
    const auto& ms = groups[key];
    std::vector<PlotSeries> series;
    for (const MetricResult* m : ms) series.push_back({m->method, {}, m->values});
    plots.push_back(histogram_plot("histogram_" + key.first + "_" + key.second,
                                   fmt::format("{} on {}: distribution over Monte-Carlo runs", key.second, key.first),
                                   key.second, ms.front()->unit, std::move(series),
                                   fmt::format("{} runs per method", ms.front()->values.size())));
  }
  return plots;
}

CdfSteps empirical_cdf(std::vector<double> samples, std::size_t max_points) {
  std::erase_if(samples, [](double v) { return !std::isfinite(v); });
  std::sort(samples.begin(), samples.end());
  CdfSteps c;
  const std::size_t n = samples.size();
  if (n == 0) return c;
  const std::size_t stride = std::max<std::size_t>(1, (n + max_points - 1) / std::max<std::size_t>(max_points, 1));
  for (std::size_t i = stride - 1; i < n; i += stride) {
    c.x.push_back(samples[i]);
    c.y.push_back(static_cast<double>(i + 1) / static_cast<double>(n));
  }
  if (c.y.back() < 1.0) {
    c.x.push_back(samples.back());
    c.y.push_back(1.0);
  }
  return c;
}

std::string plot_script(const Plot& plot) {
  std::string s =
      "set terminal svg size 720,420 dynamic noenhanced font 'sans,11' background '#ffffff'\n"
      "set encoding utf8\nset grid lc rgb '#dddddd'\nset key outside right top box\n"
      "set border lc rgb '#444444'\n";
  s += "set title " + quote(plot.title) + "\n";
  s += "set xlabel " + quote(axis_label(plot.x_label, plot.x_unit)) + "\n";
  s += "set ylabel " + quote(axis_label(plot.y_label, plot.y_unit)) + "\n";
  std::vector<std::string> terms;
  if (plot.kind == "cdf") {
    s += "set yrange [0:1]\nset key inside left top box\n";
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const CdfSteps c = empirical_cdf(plot.series[i].y);
      const std::string block = fmt::format("s{}", i);
      s += datablock(block, c.x, c.y);
      // The first sample (the reference) in black; later ones dashed in turn, so equal curves stay visible.
      terms.push_back(fmt::format("${} using 1:2 with steps lw {} dt {} lc rgb '{}' title {}", block,
                                  i == 0 ? 2.5 : 2.0, i == 0 ? 1 : static_cast<int>(i),
                                  i == 0 ? "#000000" : kColours[i % 8], quote(plot.series[i].name)));
    }
  } else if (plot.kind == "histogram") {
    std::vector<std::vector<double>> samples;
    std::size_t n = 0;
    for (const auto& ps : plot.series) {
      samples.push_back(ps.y);
      n = std::max(n, ps.y.size());
    }
    const int bins = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))) + 1, 5, 20);
    const Histogram h = histogram(samples, bins);
    s += fmt::format("set boxwidth {:.9g} absolute\nset style fill transparent solid 0.45 border\n", h.width);
    s += "set yrange [0:*]\n";
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      std::vector<double> x, y;
      for (std::size_t b = 0; b < h.counts[i].size(); ++b) {
        x.push_back(h.low + (static_cast<double>(b) + 0.5) * h.width);
        y.push_back(h.counts[i][b]);
      }
      const std::string block = fmt::format("s{}", i);
      s += datablock(block, x, y);
      terms.push_back(fmt::format("${} using 1:2 with boxes lc rgb '{}' title {}", block, kColours[i % 8],
                                  quote(plot.series[i].name)));
    }
  } else if (plot.kind == "scan_pair") {
    s += "set size ratio -1\n";
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const PlotSeries& ps = plot.series[i];
      const std::string block = fmt::format("s{}", i);
      const std::string colour = kColours[i % 8];
      if (is_segment_series(ps.name)) {
        s += segment_datablock(block, ps.x, ps.y);
        terms.push_back(fmt::format("${} using 1:2 with lines lw {} lc rgb '{}' title {}", block,
                                    ps.name.ends_with("lines") ? 2.0 : 0.6, colour, quote(ps.name)));
      } else {
        s += datablock(block, ps.x, ps.y);
        terms.push_back(
            fmt::format("${} using 1:2 with points pt 7 ps 0.35 lc rgb '{}' title {}", block, colour, quote(ps.name)));
      }
    }
  } else if (plot.kind == "scatter") {
    // Points; a series named "identity" is the line y = x (dashed), and one whose name ends in
    // "intervals" holds vertical bars as consecutive point pairs.
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const PlotSeries& ps = plot.series[i];
      const std::string block = fmt::format("s{}", i);
      if (ps.name.ends_with("intervals")) {
        s += segment_datablock(block, ps.x, ps.y);
        terms.push_back(
            fmt::format("${} using 1:2 with lines lw 3 lc rgb '{}' title {}", block, kColours[i % 8], quote(ps.name)));
      } else {
        s += datablock(block, ps.x, ps.y);
        const bool identity = ps.name == "identity";
        terms.push_back(fmt::format("${} using 1:2 with {} lc rgb '{}' title {}", block,
                                    identity ? "lines dt 2 lw 1" : "points pt 7 ps 0.8",
                                    identity ? "#888888" : kColours[i % 8], quote(ps.name)));
      }
    }
  } else {
    double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const PlotSeries& ps = plot.series[i];
      for (std::size_t k = 0; k < std::min(ps.x.size(), ps.y.size()); ++k) {
        if (!std::isfinite(ps.x[k]) || !std::isfinite(ps.y[k])) continue;
        xlo = std::min(xlo, ps.x[k]);
        xhi = std::max(xhi, ps.x[k]);
        ylo = std::min(ylo, ps.y[k]);
        yhi = std::max(yhi, ps.y[k]);
      }
      const std::string block = fmt::format("s{}", i);
      s += datablock(block, ps.x, ps.y);
      const bool truth = ps.name == "truth";
      // Binned means: lines through the bins' points; a profile's reference line (the second
      // series: a threshold) dashed, and its marked estimate (the third: value and interval) as points.
      const std::string style = plot.kind == "binned"              ? "linespoints pt 7 ps 0.7"
                                : plot.kind == "profile" && i == 1 ? "lines dt 2"
                                : plot.kind == "profile" && i >= 2 ? "linespoints pt 7 ps 0.9"
                                                                   : "lines";
      terms.push_back(fmt::format("${} using 1:2 with {} lw {} lc rgb '{}' title {}", block, style, truth ? 3.0 : 1.5,
                                  truth ? "#000000" : kColours[i % 8], quote(ps.name)));
    }
    // A plane trajectory is drawn to scale unless one side is much longer than the other
    // (a corridor), where scale would flatten it.
    if (plot.kind == "trajectory" && std::isfinite(xlo)) {
      const double w = xhi - xlo, hgt = yhi - ylo;
      if (w > 0 && hgt > 0 && w / hgt < 4.0 && hgt / w < 4.0) s += "set size ratio -1\n";
    }
    if (plot.kind == "error_vs_distance") s += "set yrange [0:*]\n";
    if (plot.kind == "binned") s += "set xzeroaxis lt -1 lw 1 lc rgb '#888888'\n";
    if (plot.kind == "profile") s += "set yrange [0:*]\n";
  }
  if (terms.empty()) {
    s += "set label 1 'no data' at graph 0.5, graph 0.5 center\nplot [0:1][0:1] NaN notitle\n";
    return s;
  }
  s += "plot ";
  for (std::size_t i = 0; i < terms.size(); ++i) s += (i ? ", \\\n     " : "") + terms[i];
  return s + "\n";
}

}  // namespace locbench::reports
