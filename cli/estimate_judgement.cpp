#include "cli/estimate_judgement.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace locbench::cli {
namespace {

// Scale factors against a nominal value: no robot is off by a factor 1000 either way.
bool is_scale(const std::string& name) {
  return name.find("scale") != std::string::npos || name == "E_d" || name == "E_b" || name == "E_o";
}

// Parameters that are a length or a scale factor: > 0, and no robot has one above 1000 (m, or
// times its nominal value).
bool is_positive_parameter(const std::string& name) {
  static const std::set<std::string> kPositive = {"wheelbase", "b",   "B",   "r_L",        "r_R",         "D_L",
                                                  "D_R",       "c_L", "c_R", "left_scale", "right_scale", "tv_scale",
                                                  "rv_scale",  "E_d", "E_b", "E_o"};
  return kPositive.count(name) > 0;
}

constexpr double kAbsurd = 1000.0;

void mark(reports::MetricResult& m, const std::string& why) {
  m.identifiable = false;
  m.note = m.note.empty() ? why : why + "; " + m.note;
}

}  // namespace

EstimateJudgement judge_estimates(reports::ExperimentResults& out, bool zero_width_unidentified) {
  EstimateJudgement j;
  std::vector<reports::MetricResult> kept;
  for (reports::MetricResult& m : out.results) {
    if (m.over != "estimate") {
      kept.push_back(std::move(m));
      continue;
    }
    const double value = m.summary.mean, se = m.summary.stddev;
    const bool identifiable = m.identifiable.value_or(true);
    if (!std::isfinite(value)) {
      j.impossible.push_back(fmt::format("{} = {}: not a finite number", m.variant, value));
      out.notes.push_back(
          fmt::format("{}: the estimate is not a finite number ({}); left out of the results.", m.variant, value));
      continue;
    }
    const double lowest = is_scale(m.variant) ? 1.0 / kAbsurd : 0.0;
    if (is_positive_parameter(m.variant) && !(value > lowest && value <= kAbsurd)) {
      const std::string why = fmt::format("{} = {:.6g} is impossible: a {} lies in ({:g}, {:g}]", m.variant, value,
                                          is_scale(m.variant) ? "scale factor" : "length", lowest, kAbsurd);
      j.impossible.push_back(why);
      mark(m, "not identifiable: " + why);
      j.unidentified.push_back(m.variant);
    } else if (identifiable && !std::isfinite(se)) {
      mark(m, "not identifiable: its standard error is not finite");
      j.unidentified.push_back(m.variant);
    } else if (identifiable && zero_width_unidentified && se == 0.0) {
      mark(m, "not identifiable: a zero-width 95% interval (standard error 0), which no finite data give");
      j.unidentified.push_back(m.variant);
    } else if (identifiable && is_positive_parameter(m.variant) && m.summary.ci95_low <= 0.0) {
      mark(m, fmt::format("not identifiable: its 95% interval [{:.4g}, {:.4g}] reaches values ≤ 0, so the data do "
                          "not determine it (not even its sign)",
                          m.summary.ci95_low, m.summary.ci95_high));
      j.unidentified.push_back(m.variant);
    }
    kept.push_back(std::move(m));
  }
  out.results = std::move(kept);
  return j;
}

}  // namespace locbench::cli
