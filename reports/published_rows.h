#pragma once
// The per-run rows of a published table beside ours.
#include <fmt/format.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "reports/report.h"

namespace locbench::reports {

// Rows "<label> 1", "<label> 2", …: published[i] beside ours[i] where ours has row i (with fewer
// runs than the thesis's, the later rows have no ours).
inline std::vector<PublishedRow> numbered_rows(const std::string& label, std::span<const double> published,
                                               std::span<const double> ours) {
  std::vector<PublishedRow> rows;
  for (std::size_t i = 0; i < published.size(); ++i) {
    PublishedRow row{fmt::format("{} {}", label, i + 1), published[i], std::nullopt};
    if (i < ours.size()) row.ours = ours[i];
    rows.push_back(row);
  }
  return rows;
}

// A published table of numbered rows (numbered_rows) beside ours.
inline PublishedComparison numbered_comparison(std::string source, std::string quantity, std::string unit,
                                               const std::string& label, std::span<const double> published,
                                               std::span<const double> ours) {
  PublishedComparison t;
  t.source = std::move(source);
  t.quantity = std::move(quantity);
  t.unit = std::move(unit);
  t.rows = numbered_rows(label, published, ours);
  return t;
}

// Column `c` of a table given as rows.
template <class Rows>
std::vector<double> table_column(const Rows& rows, std::size_t c) {
  std::vector<double> column;
  for (const auto& row : rows) column.push_back(row[c]);
  return column;
}

}  // namespace locbench::reports
