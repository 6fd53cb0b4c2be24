#pragma once
// The rules a gate enforces, loaded from JSON (see README, "CI performance gates").
#include <optional>
#include <string>
#include <vector>

namespace locbench::reports {

// A result may not get worse than its baseline by more than
// max(max_relative_worsening·|baseline|, max_absolute_worsening); with `outside_interval`,
// it must also leave the baseline's 95% interval (when the baseline has one).
struct AccuracyRule {
  std::string match = "*";  // glob over "<experiment>:<method/dataset/variant>"
  double max_relative_worsening = 0.05;
  double max_absolute_worsening = 0.0;
  bool outside_interval = true;
};

// Speed is judged as a ratio of two benchmarks measured in the same run, never as a time.
struct SpeedRatioRule {
  std::string name;
  std::string numerator;  // series key, e.g. "bench:BM_Eap/181/14"
  std::string denominator;
  std::optional<double> max_ratio;      // absolute ceiling on the current ratio
  double max_relative_increase = 0.10;  // against the baseline's ratio
  double alpha = 0.05;                  // Mann–Whitney significance with repetitions
};

struct GateRules {
  std::vector<AccuracyRule> accuracy;  // the first rule whose glob matches applies
  std::vector<SpeedRatioRule> speed_ratios;
  bool fail_on_missing = true;  // a baseline result absent now (and not skipped) fails
};

// Defaults: one accuracy rule "*" with the defaults above, no speed ratios.
GateRules default_gate_rules();
// InputError naming the file and the offending key for unknown keys or wrong types.
GateRules load_gate_rules(const std::string& path);

}  // namespace locbench::reports
