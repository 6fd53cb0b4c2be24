#include "reports/gate_rules.h"

#include <nlohmann/json.hpp>

#include "algorithms/core/errors.h"
#include "algorithms/core/json_options.h"
#include "reports/json_file.h"

namespace locbench::reports {

GateRules default_gate_rules() {
  GateRules r;
  r.accuracy.push_back(AccuracyRule{});
  return r;
}

GateRules load_gate_rules(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "rules file (JSON)");
  StrictJsonReader top(j, "rules", path);
  top.raw("comment");
  GateRules r;
  top.read("fail_on_missing", r.fail_on_missing);
  if (const nlohmann::json* accuracy = top.raw("accuracy")) {
    if (!accuracy->is_array()) top.fail("accuracy", "expected a list, found " + json_type_name(*accuracy));
    for (std::size_t i = 0; i < accuracy->size(); ++i) {
      StrictJsonReader a((*accuracy)[i], "rules.accuracy[" + std::to_string(i) + "]", path);
      a.raw("comment");
      AccuracyRule rule;
      a.read("match", rule.match);
      a.read("max_relative_worsening", rule.max_relative_worsening);
      a.read("max_absolute_worsening", rule.max_absolute_worsening);
      a.read("outside_interval", rule.outside_interval);
      a.finish();
      if (rule.max_relative_worsening < 0 || rule.max_absolute_worsening < 0) {
        a.fail("", "tolerances must be ≥ 0");
      }
      r.accuracy.push_back(rule);
    }
  } else {
    r.accuracy.push_back(AccuracyRule{});
  }
  if (const nlohmann::json* speed = top.raw("speed_ratios")) {
    if (!speed->is_array()) top.fail("speed_ratios", "expected a list, found " + json_type_name(*speed));
    for (std::size_t i = 0; i < speed->size(); ++i) {
      StrictJsonReader s((*speed)[i], "rules.speed_ratios[" + std::to_string(i) + "]", path);
      s.raw("comment");
      SpeedRatioRule rule;
      s.read("name", rule.name);
      s.read("numerator", rule.numerator);
      s.read("denominator", rule.denominator);
      if (s.has("max_ratio")) {
        double max_ratio = 0.0;
        s.read("max_ratio", max_ratio);
        rule.max_ratio = max_ratio;
      }
      s.read("max_relative_increase", rule.max_relative_increase);
      s.read("alpha", rule.alpha);
      s.finish();
      if (rule.name.empty() || rule.numerator.empty() || rule.denominator.empty()) {
        s.fail("", "name, numerator and denominator are required");
      }
      if (!(rule.alpha > 0.0 && rule.alpha < 1.0)) s.fail("alpha", "expected a number in (0, 1)");
      r.speed_ratios.push_back(rule);
    }
  }
  top.finish();
  if (r.accuracy.empty() && r.speed_ratios.empty()) {
    throw InputError(path, 0,
                     "rules: \"accuracy\" is empty and there are no \"speed_ratios\": a gate with no rule "
                     "checks nothing (omit \"accuracy\" for the default rule \"*\")");
  }
  return r;
}

}  // namespace locbench::reports
