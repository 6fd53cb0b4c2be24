#include "reports/gate_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace locbench::reports {
namespace {

bool contains(const std::string& s, const char* word) { return s.find(word) != std::string::npos; }

bool is_time_unit(const std::string& u) { return u == "s" || u == "ms" || u == "us" || u == "ns"; }

std::string number(double x) { return fmt::format("{:.17g}", x); }

}  // namespace

bool is_magnitude(const GateSeries& s) {
  if (s.is_time) return true;
  const std::string& u = s.unit;
  const bool physical = u == "m" || u == "cm" || u == "mm" || u == "rad" || u == "deg" || is_time_unit(u);
  if (!physical || s.better != "lower") return false;
  const std::string& v = s.variant;
  if (contains(v, "minus") || contains(v, "difference") || contains(v, "change")) return false;
  if (is_time_unit(u)) return true;
  static constexpr std::array<const char*, 6> kErrorWords = {"error", "rmse", "rms", "rpe", "ape", "sigma"};
  return std::any_of(kErrorWords.begin(), kErrorWords.end(), [&](const char* w) { return contains(v, w); });
}

std::string implausible(const GateSeries& s) {
  const auto finite = [](double x) { return std::isfinite(x); };
  if (!finite(s.value)) return "the value is not a finite number (" + number(s.value) + ")";
  if (!std::all_of(s.samples.begin(), s.samples.end(), finite)) return "a sample is not a finite number";
  if ((s.min && !finite(*s.min)) || (s.max && !finite(*s.max)) || !finite(s.ci95_low) || !finite(s.ci95_high)) {
    return "min, max or the 95% interval is not a finite number";
  }
  if (s.is_time) {
    const bool positive =
        s.value > 0.0 && std::all_of(s.samples.begin(), s.samples.end(), [](double t) { return t > 0.0; });
    return positive ? "" : "a benchmark time is ≤ 0 ns: no measured duration is";
  }
  if (!s.samples.empty()) {
    const auto [lo, hi] = std::minmax_element(s.samples.begin(), s.samples.end());
    double sum = 0.0, largest = 0.0;
    for (double v : s.samples) {
      sum += v;
      largest = std::max(largest, std::abs(v));
    }
    const double mean = sum / static_cast<double>(s.samples.size());
    const double tol = 1e-9 * largest;
    if (s.n != s.samples.size()) {
      return fmt::format("n = {} but `values` holds {} numbers", s.n, s.samples.size());
    }
    if (std::abs(mean - s.value) > tol) {
      return "mean " + number(s.value) + " contradicts its `values`, whose mean is " + number(mean);
    }
    if ((s.min && std::abs(*s.min - *lo) > tol) || (s.max && std::abs(*s.max - *hi) > tol)) {
      return "min or max contradicts `values` (" + number(*lo) + " … " + number(*hi) + ")";
    }
  }
  if (is_magnitude(s)) {
    double smallest = s.value;
    if (s.min) smallest = std::min(smallest, *s.min);
    for (double v : s.samples) smallest = std::min(smallest, v);
    if (smallest < 0.0) {
      return fmt::format("{} is an error, a spread or a time in {}: it cannot be negative ({})", s.variant, s.unit,
                         number(smallest));
    }
  }
  return "";
}

bool is_recorded_data(const std::string& path) {
  return !path.empty() && path != "simulated" && !contains(path, "(transcribed)");
}

bool recorded_skip(const GateSeries& s, const GateInput& current) {
  const auto sk = current.skipped.find(s.experiment);
  return sk != current.skipped.end() && sk->second.count(s.dataset);
}

std::string unbacked_skip(const GateSeries& s, const GateInput& baseline, const GateInput& current) {
  const std::string& reason = current.skipped.at(s.experiment).at(s.dataset);
  if (!contains(reason, "not found")) {
    return "the skipped case's reason does not say the data were not found (\"" + reason + "\")";
  }
  const auto cur = current.dataset_paths.find(s.experiment);
  if (cur != current.dataset_paths.end() && cur->second.count(s.dataset)) {
    return "the current report lists dataset " + s.dataset + " as read, yet skips it";
  }
  for (const auto& [key, c] : current.series) {
    if (c.experiment == s.experiment && c.dataset == s.dataset) {
      return "the current report has results of " + s.dataset + " (" + key + "), yet skips it";
    }
  }
  const auto base = baseline.dataset_paths.find(s.experiment);
  const auto path = base == baseline.dataset_paths.end() ? nullptr : &base->second;
  if (!path || !path->count(s.dataset) || !is_recorded_data(path->at(s.dataset))) {
    return "the baseline's result did not come from a data file named " + s.dataset +
           " (only absent real data may be skipped)";
  }
  return "";
}

std::string mixed_run_ids(const GateInput& in) {
  const std::pair<const std::string, std::string>* first = nullptr;
  for (const auto& entry : in.run_id_of) {
    if (!first) {
      first = &entry;
    } else if (entry.second != first->second) {
      const auto shown = [](const std::string& id) { return id.empty() ? std::string("none") : id; };
      return fmt::format("{} has run id {}, {} has {}: the folder mixes runs (a run killed over an older folder?)",
                         entry.first, shown(entry.second), first->first, shown(first->second));
    }
  }
  return "";
}

}  // namespace locbench::reports
