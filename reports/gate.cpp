#include "reports/gate.h"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <cmath>

#include "core/statistics.h"
#include "reports/gate_checks.h"

namespace locbench::reports {
namespace {

const AccuracyRule* rule_for(const std::string& key, const GateRules& rules) {
  for (const AccuracyRule& r : rules.accuracy) {
    if (fnmatch(r.match.c_str(), key.c_str(), 0) == 0) return &r;
  }
  return nullptr;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Per-repetition ratios when both series have the same number of samples; else the ratio of
// their medians alone.
std::vector<double> ratios(const GateSeries& num, const GateSeries& den) {
  std::vector<double> r;
  if (num.samples.size() == den.samples.size() && num.samples.size() > 1) {
    for (std::size_t i = 0; i < num.samples.size(); ++i) {
      r.push_back(num.samples[i] / den.samples[i]);
    }
  } else {
    r.push_back(num.value / den.value);
  }
  return r;
}

GateRow compare(const GateSeries& old_s, const GateSeries& new_s, const GateRules& rules) {
  GateRow row{old_s.key, old_s.unit, old_s.value, new_s.value, std::nullopt, "ok", ""};
  if (old_s.value != 0.0) row.relative_change = (new_s.value - old_s.value) / std::abs(old_s.value);
  if (old_s.is_time) {
    row.status = "info";
    row.detail = "times are gated only through ratios";
    return row;
  }
  const AccuracyRule* rule = rule_for(old_s.key, rules);
  if (!rule) {
    row.status = "info";
    row.detail = "no rule matches";
    return row;
  }
  const bool lower_better = old_s.better != "higher";
  double worse = lower_better ? new_s.value - old_s.value : old_s.value - new_s.value;
  if (old_s.better == "closer_to_zero") worse = std::abs(new_s.value) - std::abs(old_s.value);
  if (old_s.better == "stable") worse = std::abs(new_s.value - old_s.value);
  const double allowed = std::max(rule->max_relative_worsening * std::abs(old_s.value), rule->max_absolute_worsening);
  const bool has_interval = old_s.n >= 2 && rule->outside_interval;
  const bool outside_either = new_s.value > old_s.ci95_high || new_s.value < old_s.ci95_low;
  const bool signed_rule = old_s.better == "closer_to_zero" || old_s.better == "stable";
  const bool outside =
      signed_rule ? outside_either : (lower_better ? new_s.value > old_s.ci95_high : new_s.value < old_s.ci95_low);
  const bool beyond =
      signed_rule ? outside_either : (lower_better ? new_s.value < old_s.ci95_low : new_s.value > old_s.ci95_high);
  if (worse > allowed && (!has_interval || outside)) {
    row.status = "regressed";
    row.detail = fmt::format("worse by {:.4g} {} (allowed {:.4g}{}; rule \"{}\")", worse, old_s.unit, allowed,
                             has_interval ? ", and outside the baseline's 95% interval" : "", rule->match);
  } else if (worse < -allowed && (!has_interval || beyond)) {
    row.status = "improved";
  } else if (worse > allowed) {
    row.detail = "worse than the tolerance but inside the baseline's 95% interval";
  }
  return row;
}

GateRatioRow compare_ratio(const SpeedRatioRule& rule, const GateInput& baseline, const GateInput& current) {
  GateRatioRow row;
  row.name = rule.name;
  const auto find = [](const GateInput& in, const std::string& k) -> const GateSeries* {
    const auto it = in.series.find(k);
    return it == in.series.end() ? nullptr : &it->second;
  };
  const GateSeries* on = find(baseline, rule.numerator);
  const GateSeries* od = find(baseline, rule.denominator);
  const GateSeries* nn = find(current, rule.numerator);
  const GateSeries* nd = find(current, rule.denominator);
  if (!nn || !nd) {
    row.status = "missing";
    row.detail = "current run lacks " + (!nn ? rule.numerator : rule.denominator);
    return row;
  }
  // Fail closed: a time ≤ 0 or not finite (a 0 ns / 0 ns pair) makes no ratio.
  for (const GateSeries* s : {nn, nd, on, od}) {
    if (s && !implausible(*s).empty()) {
      row.status = "invalid";
      row.detail = s->key + ": " + implausible(*s);
      return row;
    }
  }
  const std::vector<double> now = ratios(*nn, *nd);
  row.new_ratio = median(now);
  row.status = "ok";
  if (rule.max_ratio && *row.new_ratio > *rule.max_ratio) {
    row.status = "regressed";
    row.detail = fmt::format("ratio {:.4g} exceeds the ceiling {:.4g}", *row.new_ratio, *rule.max_ratio);
    return row;
  }
  if (!on || !od) {
    row.detail = "no baseline ratio";
    return row;
  }
  const std::vector<double> before = ratios(*on, *od);
  row.old_ratio = median(before);
  row.relative_change = (*row.new_ratio - *row.old_ratio) / std::abs(*row.old_ratio);
  const bool grew = *row.relative_change > rule.max_relative_increase;
  if (now.size() >= 2 && before.size() >= 2) {
    row.p_value = mann_whitney_u(now, before).p_greater;
    if (grew && *row.p_value < rule.alpha) {
      row.status = "regressed";
      row.detail =
          fmt::format("ratio grew {:+.1f}% (p = {:.3g} < {})", 100 * *row.relative_change, *row.p_value, rule.alpha);
    } else if (grew) {
      row.detail = fmt::format("ratio grew {:+.1f}% but p = {:.3g} ≥ {}: not significant", 100 * *row.relative_change,
                               *row.p_value, rule.alpha);
    }
  } else if (grew) {
    row.status = "regressed";
    row.detail = fmt::format("ratio grew {:+.1f}% (no repetitions: no significance test)", 100 * *row.relative_change);
  }
  if (row.status == "ok" && *row.relative_change < -rule.max_relative_increase) {
    row.status = "improved";
  }
  return row;
}

std::string gate_number(const std::optional<double>& v) { return v ? fmt::format("{:.6g}", *v) : std::string("—"); }
std::string pct(const std::optional<double>& v) { return v ? fmt::format("{:+.2f}%", 100.0 * *v) : std::string("—"); }

}  // namespace

namespace {

// A row that fails because a series could not have been measured (gate_checks.h).
GateRow invalid_row(const GateSeries& s, const std::optional<double>& old_v, const std::optional<double>& new_v,
                    const std::string& detail) {
  return {s.key, s.unit, old_v, new_v, std::nullopt, "invalid", detail};
}

// Fail closed: the baseline read recorded data, and not one of those results was compared now
// (all skipped or missing): a gate on no real data cannot pass.
void require_some_recorded_data(const GateInput& baseline, const GateInput& current, GateVerdict& v) {
  std::size_t recorded = 0, compared = 0;
  for (const auto& [key, s] : baseline.series) {
    const auto ds = baseline.dataset_paths.find(s.experiment);
    if (ds == baseline.dataset_paths.end() || !ds->second.count(s.dataset) ||
        !is_recorded_data(ds->second.at(s.dataset))) {
      continue;
    }
    ++recorded;
    if (current.series.count(key)) ++compared;
  }
  if (recorded > 0 && compared == 0) {
    v.rows.push_back({"recorded data", "", std::nullopt, std::nullopt, std::nullopt, "missing",
                      fmt::format("the baseline has {} results from recorded data and none was compared now "
                                  "(all skipped or missing): a gate on no real data cannot pass",
                                  recorded)});
    ++v.failures;
  }
}

}  // namespace

GateVerdict evaluate_gate(const GateInput& baseline, const GateInput& current, const GateRules& rules) {
  GateVerdict v;
  double log_sum = 0.0;
  std::size_t log_n = 0;
  for (const auto& [key, old_s] : baseline.series) {
    const auto it = current.series.find(key);
    const std::string bad_old = implausible(old_s);
    if (it == current.series.end()) {
      GateRow row{key, old_s.unit, old_s.value, std::nullopt, std::nullopt, "missing", ""};
      const std::string unbacked = recorded_skip(old_s, current) ? unbacked_skip(old_s, baseline, current) : "";
      if (!bad_old.empty()) {
        row = invalid_row(old_s, old_s.value, std::nullopt, "baseline: " + bad_old);
        ++v.failures;
      } else if (recorded_skip(old_s, current) && unbacked.empty()) {
        row.status = "skipped";
        row.detail = "the current run skipped dataset " + old_s.dataset + " (data not found)";
      } else if (!unbacked.empty()) {
        row.detail = "skip not backed: " + unbacked;
        ++v.failures;
      } else if (rules.fail_on_missing && !old_s.is_time) {
        row.detail = "present in the baseline, absent now";
        ++v.failures;
      }
      v.rows.push_back(std::move(row));
      continue;
    }
    const std::string bad_new = implausible(it->second);
    if (!bad_old.empty() || !bad_new.empty()) {
      v.rows.push_back(invalid_row(old_s, old_s.value, it->second.value,
                                   bad_new.empty() ? "baseline: " + bad_old : "current: " + bad_new));
      ++v.failures;
      continue;
    }
    GateRow row = compare(old_s, it->second, rules);
    if (row.status == "regressed") ++v.failures;
    if (old_s.value > 0.0 && it->second.value > 0.0) {
      log_sum += std::log(it->second.value / old_s.value);
      ++log_n;
    }
    v.rows.push_back(std::move(row));
  }
  for (const auto& [key, s] : current.series) {
    if (!baseline.series.count(key)) {
      const std::string bad = implausible(s);
      if (!bad.empty()) {
        v.rows.push_back(invalid_row(s, std::nullopt, s.value, "current: " + bad));
        ++v.failures;
      } else {
        v.rows.push_back({key, s.unit, std::nullopt, s.value, std::nullopt, "new", ""});
      }
    }
  }
  if (log_n > 0) v.geomean_ratio = std::exp(log_sum / static_cast<double>(log_n));
  // Fail closed: an accuracy rule that matches no current result checks nothing — its results
  // went missing (absent data, a typo in --data) — unless the run said, with provenance, that
  // it skipped them.
  for (const AccuracyRule& r : rules.accuracy) {
    bool matched = false, skipped = false;
    for (const auto& [key, s] : current.series) matched = matched || fnmatch(r.match.c_str(), key.c_str(), 0) == 0;
    for (const auto& [key, s] : baseline.series) {
      if (fnmatch(r.match.c_str(), key.c_str(), 0) == 0 && recorded_skip(s, current) &&
          unbacked_skip(s, baseline, current).empty()) {
        skipped = true;
      }
    }
    if (matched || skipped) continue;
    v.rows.push_back({"rule " + r.match, "", std::nullopt, std::nullopt, std::nullopt, "missing",
                      "no current result matches this rule: its results are missing"});
    ++v.failures;
  }
  require_some_recorded_data(baseline, current, v);
  for (const SpeedRatioRule& r : rules.speed_ratios) {
    GateRatioRow row = compare_ratio(r, baseline, current);
    if (row.status == "regressed" || row.status == "missing" || row.status == "invalid") ++v.failures;
    v.ratios.push_back(std::move(row));
  }
  return v;
}

void fail_mixed_runs(const GateInput& current, GateVerdict& v) {
  const std::string mixed = mixed_run_ids(current);
  if (mixed.empty()) return;
  v.rows.push_back({"run id", "", std::nullopt, std::nullopt, std::nullopt, "mixed", mixed});
  ++v.failures;
}

std::string gate_table(const GateVerdict& v) {
  std::size_t w = 9;
  for (const GateRow& r : v.rows) w = std::max(w, r.key.size());
  std::string out = fmt::format("{:<{}}  {:>12}  {:>12}  {:>9}  {:<9}  {}\n", "result", w, "old", "new", "change",
                                "status", "detail");
  for (const GateRow& r : v.rows) {
    out += fmt::format("{:<{}}  {:>12}  {:>12}  {:>9}  {:<9}  {}\n", r.key, w, gate_number(r.old_value),
                       gate_number(r.new_value), pct(r.relative_change), r.status, r.detail);
  }
  if (v.geomean_ratio) {
    out += fmt::format("{:<{}}  {:>12}  {:>12}  {:>9}\n", "OVERALL_GEOMEAN", w, "", "", pct(*v.geomean_ratio - 1.0));
  }
  for (const GateRatioRow& r : v.ratios) {
    out += fmt::format("ratio {:<{}}  {:>12}  {:>12}  {:>9}  {:<9}  {}{}\n", r.name, w - 6, gate_number(r.old_ratio),
                       gate_number(r.new_ratio), pct(r.relative_change), r.status,
                       r.p_value ? fmt::format("p = {:.3g}; ", *r.p_value) : "", r.detail);
  }
  out += v.passed() ? "gate: PASSED\n"
                    : fmt::format("gate: FAILED ({} failing check{})\n", v.failures, v.failures == 1 ? "" : "s");
  return out;
}

std::string gate_markdown(const GateVerdict& v) {
  std::string out = v.passed() ? "### locbench gate: ✅ passed\n\n"
                               : fmt::format("### locbench gate: ❌ failed ({} failing)\n\n", v.failures);
  out += "| result | old | new | change | status | detail |\n|---|---:|---:|---:|---|---|\n";
  for (const GateRow& r : v.rows) {
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", r.key, gate_number(r.old_value), gate_number(r.new_value),
                       pct(r.relative_change), r.status, r.detail);
  }
  if (v.geomean_ratio) {
    out += fmt::format("| **geometric mean** | | | {} | | |\n", pct(*v.geomean_ratio - 1.0));
  }
  if (!v.ratios.empty()) {
    out +=
        "\n| speed ratio | old | new | change | p | status | detail |\n"
        "|---|---:|---:|---:|---:|---|---|\n";
    for (const GateRatioRow& r : v.ratios) {
      out += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", r.name, gate_number(r.old_ratio),
                         gate_number(r.new_ratio), pct(r.relative_change), gate_number(r.p_value), r.status, r.detail);
    }
  }
  return out;
}

nlohmann::json gate_json(const GateVerdict& v, const GateInput& baseline, const GateInput& current) {
  const auto opt = [](const std::optional<double>& x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["schema"] = "locbench.gate/1";
  j["passed"] = v.passed();
  j["failures"] = v.failures;
  j["baseline"] = baseline.sources;
  j["current"] = current.sources;
  j["geomean_ratio"] = opt(v.geomean_ratio);
  j["rows"] = nlohmann::json::array();
  for (const GateRow& r : v.rows) {
    j["rows"].push_back({{"name", r.key},
                         {"unit", r.unit},
                         {"old", opt(r.old_value)},
                         {"new", opt(r.new_value)},
                         {"relative_change", opt(r.relative_change)},
                         {"status", r.status},
                         {"detail", r.detail}});
  }
  j["ratios"] = nlohmann::json::array();
  for (const GateRatioRow& r : v.ratios) {
    j["ratios"].push_back({{"name", r.name},
                           {"old", opt(r.old_ratio)},
                           {"new", opt(r.new_ratio)},
                           {"relative_change", opt(r.relative_change)},
                           {"p_value", opt(r.p_value)},
                           {"status", r.status},
                           {"detail", r.detail}});
  }
  return j;
}

}  // namespace locbench::reports
