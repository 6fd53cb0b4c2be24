#include "reports/summary_table.h"

#include <fmt/format.h>

#include <algorithm>

namespace locbench::reports {

std::string summary_table(const std::vector<Report>& reports) {
  std::size_t w = 6;
  for (const Report& r : reports) {
    for (const MetricResult& m : r.body.results) w = std::max(w, m.name().size());
  }
  std::string out = fmt::format("{:<{}}  {:>5}  {:>12}  {:>12}  {:>27}  {}\n", "result", w, "n", "mean", "std",
                                "95% interval", "unit");
  out += std::string(w + 5 + 12 + 12 + 27 + 14, '-') + "\n";
  for (const Report& r : reports) {
    for (const MetricResult& m : r.body.results) {
      const Summary& s = m.summary;
      if (m.identifiable.has_value() && !*m.identifiable) {
        out += fmt::format("{:<{}}  {:>5}  {:>12.6g}  {:>12}  {:>27}  {}\n", m.name(), w, s.n, s.mean, "—",
                           "not identifiable", m.unit);
        continue;
      }
      out += fmt::format("{:<{}}  {:>5}  {:>12.6g}  {:>12.6g}  [{:>12.6g}, {:>12.6g}]  {}\n", m.name(), w, s.n, s.mean,
                         s.stddev, s.ci95_low, s.ci95_high, m.unit);
    }
    for (const CaseNote& c : r.body.cases) {
      out += fmt::format("{:<{}}  {}: {}\n", c.name, w, c.status, c.reason);
    }
  }
  return out;
}

}  // namespace locbench::reports
