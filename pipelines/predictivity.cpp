#include "pipelines/predictivity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/statistics.h"

namespace locbench::experiments {
namespace {

bool finite_cell(const PredictivityCell& c) {
  return !c.real_diverged && std::isfinite(c.real) && std::isfinite(c.nominal.median) &&
         std::isfinite(c.extended.median);
}

double mmrv(const std::vector<const PredictivityCell*>& cells, bool extended) {
  std::map<std::string, std::vector<const PredictivityCell*>> by_log;
  for (const PredictivityCell* c : cells) by_log[c->log].push_back(c);
  double sum = 0.0;
  std::size_t logs = 0;
  for (const auto& [log, group] : by_log) {
    double scale = 0.0;
    for (const PredictivityCell* c : group) scale += std::abs(c->real);
    scale /= static_cast<double>(group.size());
    if (!(scale > 0.0)) continue;
    double log_sum = 0.0;
    for (const PredictivityCell* a : group) {
      double worst = 0.0;
      const double sa = extended ? a->extended.median : a->nominal.median;
      for (const PredictivityCell* b : group) {
        const double sb = extended ? b->extended.median : b->nominal.median;
        if ((sa < sb) != (a->real < b->real)) worst = std::max(worst, std::abs(a->real - b->real) / scale);
      }
      log_sum += worst;
    }
    sum += log_sum / static_cast<double>(group.size());
    ++logs;
  }
  return logs > 0 ? sum / static_cast<double>(logs) : 0.0;
}

}  // namespace

PredictiveInterval predictive_interval(std::vector<double> runs) {
  if (runs.empty()) throw std::invalid_argument("predictive_interval: no runs");
  for (double& v : runs)
    if (!std::isfinite(v)) v = std::numeric_limits<double>::infinity();
  PredictiveInterval p;
  p.runs = runs.size();
  p.low = quantile(runs, 0.025);
  p.median = quantile(runs, 0.5);
  p.high = quantile(runs, 0.975);
  return p;
}

MetricPredictivity predictivity(const std::vector<PredictivityCell>& cells) {
  MetricPredictivity m;
  m.cells = cells.size();
  std::vector<const PredictivityCell*> usable;
  std::vector<double> real, nominal, extended;
  for (const PredictivityCell& c : cells) {
    for (auto [t, interval] : {std::pair{&m.nominal, &c.nominal}, std::pair{&m.extended, &c.extended}}) {
      t->covered += interval->covers(c.real) ? 1 : 0;
      t->above += c.real > interval->high ? 1 : 0;
      t->below += c.real < interval->low ? 1 : 0;
    }
    if (c.sensor) {
      ++m.sensor_cells;
      const bool sensor_covers = c.sensor->covers(c.real);
      m.sensor_covered += sensor_covers ? 1 : 0;
      if (!c.extended.covers(c.real)) ++(sensor_covers ? m.extended_misses_of_motion : m.extended_misses_of_sensor);
    }
    if (!finite_cell(c)) continue;
    usable.push_back(&c);
    real.push_back(c.real);
    nominal.push_back(c.nominal.median);
    extended.push_back(c.extended.median);
  }
  m.compared = usable.size();
  if (usable.size() >= 2) {
    const auto positive = [](const std::vector<double>& v) {
      return std::all_of(v.begin(), v.end(), [](double x) { return x > 0.0; });
    };
    m.log_scale = positive(real) && positive(nominal) && positive(extended);
    const auto scale = [&](std::vector<double> v) {
      if (m.log_scale)
        for (double& x : v) x = std::log(x);
      return v;
    };
    m.nominal.pearson = pearson_correlation(scale(nominal), scale(real));
    m.extended.pearson = pearson_correlation(scale(extended), scale(real));
    m.nominal.spearman = spearman_correlation(nominal, real);
    m.extended.spearman = spearman_correlation(extended, real);
  }
  m.nominal.mmrv = mmrv(usable, false);
  m.extended.mmrv = mmrv(usable, true);
  return m;
}

std::string excess_source(double real, double low, double high, const PredictiveInterval& sensor) {
  if (real > high) return sensor.median > high ? "motion" : sensor.high <= high ? "sensor" : "both";
  if (real < low) return sensor.median < low ? "motion" : sensor.low >= low ? "sensor" : "both";
  return "";
}

}  // namespace locbench::experiments
