#include "reports/gate_rules.h"

#include <nlohmann/json.hpp>

#include "core/errors.h"
#include "core/json_file.h"
#include "core/json_options.h"

namespace locbench::reports {
namespace {

// Reads each object of the list at `key` with its own strict reader ("rules.key[i]", the
// "comment" key allowed); returns false when the key is absent.
template <class F>
bool each_rule(StrictJsonReader& top, const char* key, F read_one) {
  const nlohmann::json* list = top.raw(key);
  if (!list) return false;
  if (!list->is_array()) top.fail(key, "expected a list, found " + json_type_name(*list));
  for (std::size_t i = 0; i < list->size(); ++i) {
    StrictJsonReader item((*list)[i], top.path_of(key) + "[" + std::to_string(i) + "]", top.source());
    item.raw("comment");
    read_one(item);
    item.finish();
  }
  return true;
}

}  // namespace

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
  const bool has_accuracy = each_rule(top, "accuracy", [&](StrictJsonReader& a) {
    AccuracyRule rule;
    a.read("match", rule.match);
    a.read("max_relative_worsening", rule.max_relative_worsening);
    a.read("max_absolute_worsening", rule.max_absolute_worsening);
    a.read("outside_interval", rule.outside_interval);
    if (rule.max_relative_worsening < 0 || rule.max_absolute_worsening < 0) {
      a.fail("", "tolerances must be ≥ 0");
    }
    r.accuracy.push_back(rule);
  });
  if (!has_accuracy) r.accuracy.push_back(AccuracyRule{});
  each_rule(top, "speed_ratios", [&](StrictJsonReader& s) {
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
    if (rule.name.empty() || rule.numerator.empty() || rule.denominator.empty()) {
      s.fail("", "name, numerator and denominator are required");
    }
    if (!(rule.alpha > 0.0 && rule.alpha < 1.0)) s.fail("alpha", "expected a number in (0, 1)");
    r.speed_ratios.push_back(rule);
  });
  top.finish();
  if (r.accuracy.empty() && r.speed_ratios.empty()) {
    throw InputError(path, 0,
                     "rules: \"accuracy\" is empty and there are no \"speed_ratios\": a gate with no rule "
                     "checks nothing (omit \"accuracy\" for the default rule \"*\")");
  }
  return r;
}

}  // namespace locbench::reports
