#include "pipelines/predictivity_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace locbench::experiments {
namespace {

std::string interval_text(const PredictiveInterval& p, double real) {
  return fmt::format("[{:.4g}, {:.4g}] {}", p.low, p.high, p.covers(real) ? "covered" : "MISSED");
}

reports::MetricResult count(const std::string& twin, const std::string& variant, double value, std::size_t n,
                            std::string better, std::string note) {
  reports::MetricResult r = reports::make_estimate(twin, "all_logs", variant, "", value, 0.0, n);
  r.better = std::move(better);
  r.note = std::move(note);
  return r;
}

reports::Plot scatter_chart(const std::string& name, const std::string& title, const std::string& x_label,
                            const std::string& x_unit, const std::string& y_label, const std::string& y_unit) {
  reports::Plot p;
  p.name = name;
  p.kind = "scatter";
  p.title = title;
  p.x_label = x_label;
  p.x_unit = x_unit;
  p.y_label = y_label;
  p.y_unit = y_unit;
  return p;
}

}  // namespace

std::string cell_lines(const std::vector<PredictivityCell>& cells, const std::string& unit) {
  std::string s;
  for (const PredictivityCell& c : cells) {
    s += fmt::format("\n    {:<18} real {:.4g}{} | nominal twin {} | extended twin {}", c.method, c.real,
                     unit.empty() ? "" : " " + unit, interval_text(c.nominal, c.real),
                     interval_text(c.extended, c.real));
    if (c.sensor) s += " | sensor twin " + interval_text(*c.sensor, c.real);
  }
  return s;
}

std::vector<reports::MetricResult> predictivity_results(const std::string& metric, const MetricPredictivity& m) {
  std::vector<reports::MetricResult> out;
  for (const auto& [twin, t] : {std::pair{"nominal_twin", m.nominal}, std::pair{"extended_twin", m.extended}}) {
    out.push_back(count(twin, metric + "_covered_fraction",
                        m.cells ? static_cast<double>(t.covered) / static_cast<double>(m.cells) : 0.0, m.cells,
                        "higher", "cells whose real value the twin's 95% predictive interval contains"));
    if (m.compared < kMinCorrelatedCells) continue;
    out.push_back(count(twin, metric + "_pearson_r", t.pearson, m.compared, "higher",
                        "Pearson r of the twin's prediction (median) and the real value across methods × logs"));
    out.push_back(count(twin, metric + "_spearman_rho", t.spearman, m.compared, "higher", "Spearman ρ, as above"));
    out.push_back(count(twin, metric + "_mmrv", t.mmrv, m.compared, "lower",
                        "mean maximum rank violation of the methods per log, relative to the log's mean real value"));
  }
  if (m.sensor_cells == 0) return out;
  out.push_back(count("sensor_twin", metric + "_covered_fraction",
                      static_cast<double>(m.sensor_covered) / static_cast<double>(m.sensor_cells), m.sensor_cells,
                      "higher",
                      "cells whose real value the sensor twin's (the log's own motion, the fitted sensor) 95% "
                      "predictive interval contains"));
  out.push_back(count("extended_twin", metric + "_misses_of_the_motion_model",
                      static_cast<double>(m.extended_misses_of_motion), m.sensor_cells, "lower",
                      "cells the extended twin misses and the sensor twin covers: with the log's own motion the "
                      "forecast holds"));
  out.push_back(count("extended_twin", metric + "_misses_of_the_sensor_model",
                      static_cast<double>(m.extended_misses_of_sensor), m.sensor_cells, "lower",
                      "cells the extended twin and the sensor twin both miss: the fitted sensor does not forecast "
                      "the log even with its own motion"));
  return out;
}

std::vector<reports::MetricResult> residual_ks_results(std::size_t cells, std::size_t nominal, std::size_t extended) {
  std::vector<reports::MetricResult> out;
  for (const auto& [twin, n] : {std::pair{"nominal_twin", nominal}, std::pair{"extended_twin", extended}}) {
    out.push_back(count(twin, "residual_ks_indistinguishable_fraction",
                        cells ? static_cast<double>(n) / static_cast<double>(cells) : 0.0, cells, "higher",
                        "cells (log × component) whose 1 s window residuals the KS block bootstrap cannot tell "
                        "from the log's (p > 0.05)"));
  }
  return out;
}

reports::Plot interval_plot(const std::string& name, const std::string& title, const std::string& unit,
                            const std::vector<PredictivityCell>& cells) {
  reports::Plot p = scatter_chart(name, title, "method", "", "value", unit);
  reports::PlotSeries real{"real", {}, {}}, nominal{"nominal twin intervals", {}, {}},
      extended{"extended twin intervals", {}, {}}, sensor{"sensor twin intervals", {}, {}};
  std::string order;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto x = static_cast<double>(i);
    const PredictivityCell& c = cells[i];
    real.x.push_back(x);
    real.y.push_back(c.real);
    for (auto [series, interval, dx] :
         {std::tuple{&nominal, &c.nominal, -0.15}, std::tuple{&extended, &c.extended, 0.15}}) {
      if (!std::isfinite(interval->low) || !std::isfinite(interval->high)) continue;
      series->x.insert(series->x.end(), {x + dx, x + dx});
      series->y.insert(series->y.end(), {interval->low, interval->high});
    }
    if (c.sensor && std::isfinite(c.sensor->low) && std::isfinite(c.sensor->high)) {
      sensor.x.insert(sensor.x.end(), {x + 0.3, x + 0.3});
      sensor.y.insert(sensor.y.end(), {c.sensor->low, c.sensor->high});
    }
    order += fmt::format("{}{} = {}", i ? ", " : "", i, c.method);
  }
  p.series = {real, nominal, extended};
  if (!sensor.x.empty()) p.series.push_back(sensor);
  p.note = fmt::format("x: {}; bars: the twins' 95% predictive intervals ({} seeded runs each)", order,
                       cells.empty() ? 0 : cells.front().nominal.runs);
  return p;
}

reports::Plot scatter_plot(const std::string& name, const std::string& title, const std::string& unit,
                           const std::vector<PredictivityCell>& cells) {
  reports::Plot p = scatter_chart(name, title, "real", unit, "twin's prediction (median)", unit);
  reports::PlotSeries nominal{"nominal twin", {}, {}}, extended{"extended twin", {}, {}}, identity{"identity", {}, {}};
  double lo = INFINITY, hi = -INFINITY;
  for (const PredictivityCell& c : cells) {
    if (!std::isfinite(c.real)) continue;
    for (auto [series, prediction] : {std::pair{&nominal, c.nominal.median}, std::pair{&extended, c.extended.median}}) {
      if (!std::isfinite(prediction)) continue;
      series->x.push_back(c.real);
      series->y.push_back(prediction);
      lo = std::min({lo, c.real, prediction});
      hi = std::max({hi, c.real, prediction});
    }
  }
  if (std::isfinite(lo)) identity = {"identity", {lo, hi}, {lo, hi}};
  p.series = {nominal, extended, identity};
  p.note = "one point per method and log; cells with a non-finite value are left out";
  return p;
}

}  // namespace locbench::experiments
