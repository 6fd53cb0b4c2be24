#include "reports/findings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace locbench::reports {

std::string to_string(Verdict v) {
  switch (v) {
    case Verdict::kReproduced: return "reproduced";
    case Verdict::kNotReproduced: return "not reproduced";
    case Verdict::kThesisWrong: return "the thesis is wrong";
    case Verdict::kNoVerdict: break;
  }
  return "no verdict";
}

double row_tolerance(const PublishedComparison& c, const PublishedRow& row) {
  if (row.tolerance) return *row.tolerance;
  return std::max(c.tolerance.value_or(0.0),
                  c.relative_tolerance.value_or(0.0) * std::abs(row.published.value_or(0.0)));
}

TableFinding table_finding(const PublishedComparison& c) {
  TableFinding f;
  const std::string unit = c.unit.empty() ? "" : " " + c.unit;
  // The worst row outside tolerance that no check explains (else the worst explained one).
  double worst_excess = -1.0, worst_explained = -1.0;
  const PublishedRow* worst = nullptr;
  const PublishedRow* explained = nullptr;
  double worst_tol = 0.0, explained_tol = 0.0;
  for (const PublishedRow& r : c.rows) {
    if (!r.compared || !r.published || !r.ours || !std::isfinite(*r.published) || !std::isfinite(*r.ours)) continue;
    ++f.compared;
    const double tol = row_tolerance(c, r);
    const double diff = std::abs(*r.ours - *r.published);
    if (diff <= tol) {
      ++f.within;
      continue;
    }
    const bool confirmed = r.check && std::isfinite(*r.check) && std::abs(*r.check - *r.ours) <= tol &&
                           std::abs(*r.check - *r.published) > tol;
    if (confirmed) {
      ++f.thesis_wrong;
      if (diff - tol > worst_explained) {
        worst_explained = diff - tol;
        explained = &r;
        explained_tol = tol;
      }
    } else if (diff - tol > worst_excess) {
      worst_excess = diff - tol;
      worst = &r;
      worst_tol = tol;
    }
  }
  const bool per_row =
      std::any_of(c.rows.begin(), c.rows.end(), [](const PublishedRow& r) { return r.tolerance.has_value(); });
  if ((!c.tolerance && !c.relative_tolerance && !per_row) || f.compared == 0) {
    f.reason =
        f.compared == 0 ? "no row has both a published and a measured figure" : "the experiment states no tolerance";
    return f;
  }
  const std::string tol_text =
      per_row ? std::string("its tolerance")
      : c.relative_tolerance && c.tolerance
          ? fmt::format("±max({:.4g}{}, {:.4g}%)", *c.tolerance, unit, 100.0 * *c.relative_tolerance)
      : c.relative_tolerance ? fmt::format("±{:.4g}%", 100.0 * *c.relative_tolerance)
                             : fmt::format("±{:.4g}{}", *c.tolerance, unit);
  const auto describe = [&](const PublishedRow& r, double tol) {
    return fmt::format("{}: ours {:.4g} vs published {:.4g}{} (off by {:.4g}, tolerance {:.4g}{})", r.label, *r.ours,
                       *r.published, unit, std::abs(*r.ours - *r.published), tol,
                       r.check ? fmt::format("; computed another way: {:.4g}", *r.check) : "");
  };
  if (f.within == f.compared) {
    f.verdict = Verdict::kReproduced;
    f.reason = fmt::format("all {} rows within {}", f.compared, tol_text);
  } else if (worst == nullptr) {
    f.verdict = Verdict::kThesisWrong;
    f.reason = fmt::format("{} of {} rows within {}; {} contradict the thesis, ours confirmed another way; worst: {}",
                           f.within, f.compared, tol_text, f.thesis_wrong, describe(*explained, explained_tol));
  } else {
    f.verdict = Verdict::kNotReproduced;
    f.reason = fmt::format(
        "{} of {} rows within {}{}; worst: {}", f.within, f.compared, tol_text,
        f.thesis_wrong ? fmt::format(", {} contradict the thesis (ours confirmed another way)", f.thesis_wrong) : "",
        describe(*worst, worst_tol));
  }
  if (!c.tolerance_basis.empty()) f.reason += " (tolerance: " + c.tolerance_basis + ")";
  return f;
}

void compare_means_only(PublishedComparison& c, const std::vector<double>& published_runs) {
  double m = 0.0, ss = 0.0;
  for (double v : published_runs) m += v / static_cast<double>(published_runs.size());
  for (double v : published_runs) ss += (v - m) * (v - m);
  const double sd = published_runs.size() > 1 ? std::sqrt(ss / static_cast<double>(published_runs.size() - 1)) : 0.0;
  for (PublishedRow& r : c.rows) r.compared = r.label.starts_with("mean");
  c.tolerance = sd;
  c.tolerance_basis = fmt::format(
      "runs not paired with the thesis's: a mean is reproduced within one standard "
      "deviation of the thesis's {} runs, {:.4g}{}",
      published_runs.size(), sd, c.unit.empty() ? "" : " " + c.unit);
}

}  // namespace locbench::reports
