#include "reports/report.h"

namespace locbench::reports {

MetricResult make_metric(std::string method, std::string dataset, std::string variant,
                         std::string unit, std::string over, std::span<const double> values,
                         bool keep_values) {
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

}  // namespace locbench::reports
