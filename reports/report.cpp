#include "reports/report.h"

#include <algorithm>
#include <cmath>

namespace locbench::reports {

MetricResult make_metric(std::string method, std::string dataset, std::string variant, std::string unit,
                         std::string over, std::span<const double> values, bool keep_values) {
  MetricResult m;
  m.method = std::move(method);
  m.dataset = std::move(dataset);
  m.variant = std::move(variant);
  m.unit = std::move(unit);
  m.over = std::move(over);
  m.summary = summarize(values);
  if (keep_values) m.values.assign(values.begin(), values.end());
  return m;
}

std::string key_part(std::string name) {
  for (char& c : name) {
    if (c == '/' || c == ':' || c == '.') c = '_';
  }
  return name;
}

MetricResult make_estimate(std::string method, std::string dataset, std::string variant, std::string unit, double value,
                           double standard_error, std::size_t n) {
  MetricResult m;
  m.method = std::move(method);
  m.dataset = std::move(dataset);
  m.variant = std::move(variant);
  m.unit = std::move(unit);
  m.over = "estimate";
  m.better = "stable";
  m.summary.n = std::max<std::size_t>(n, 1);
  m.summary.mean = m.summary.median = m.summary.min = m.summary.max = value;
  if (std::isfinite(standard_error)) {
    m.summary.stddev = standard_error;
    m.summary.ci95_low = value - 1.959963984540054 * standard_error;
    m.summary.ci95_high = value + 1.959963984540054 * standard_error;
  } else {
    m.summary.ci95_low = m.summary.ci95_high = value;
    m.identifiable = false;
  }
  return m;
}

}  // namespace locbench::reports
