#include "reports/gate_rules.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "core/errors.h"
#include "reports/json_file.h"

namespace locbench::reports {
namespace {
using nlohmann::json;

void only_keys(const json& j, const std::set<std::string>& allowed, const std::string& file,
               const std::string& where) {
  if (!j.is_object()) throw InputError(file, 0, where + ": expected an object");
  for (const auto& [k, v] : j.items()) {
    if (!allowed.count(k)) throw InputError(file, 0, where + ": unknown key \"" + k + "\"");
  }
}

template <typename T>
void read(const json& j, const char* key, T& out, const std::string& file,
          const std::string& where) {
  if (!j.contains(key)) return;
  try {
    out = j.at(key).get<T>();
  } catch (const json::exception&) {
    throw InputError(file, 0, where + "." + key + ": wrong type");
  }
}

}  // namespace

GateRules default_gate_rules() {
  GateRules r;
  r.accuracy.push_back(AccuracyRule{});
  return r;
}

GateRules load_gate_rules(const std::string& path) {
  const json j = read_json_file(path, "rules file (JSON)");
  only_keys(j, {"accuracy", "speed_ratios", "fail_on_missing", "comment"}, path, "rules");
  GateRules r;
  read(j, "fail_on_missing", r.fail_on_missing, path, "rules");
  if (j.contains("accuracy")) {
    if (!j["accuracy"].is_array()) throw InputError(path, 0, "rules.accuracy: expected a list");
    for (std::size_t i = 0; i < j["accuracy"].size(); ++i) {
      const json& a = j["accuracy"][i];
      const std::string where = "rules.accuracy[" + std::to_string(i) + "]";
      only_keys(a, {"match", "max_relative_worsening", "max_absolute_worsening",
                    "outside_interval", "comment"}, path, where);
      AccuracyRule rule;
      read(a, "match", rule.match, path, where);
      read(a, "max_relative_worsening", rule.max_relative_worsening, path, where);
      read(a, "max_absolute_worsening", rule.max_absolute_worsening, path, where);
      read(a, "outside_interval", rule.outside_interval, path, where);
      if (rule.max_relative_worsening < 0 || rule.max_absolute_worsening < 0) {
        throw InputError(path, 0, where + ": tolerances must be ≥ 0");
      }
      r.accuracy.push_back(rule);
    }
  } else {
    r.accuracy.push_back(AccuracyRule{});
  }
  if (j.contains("speed_ratios")) {
    if (!j["speed_ratios"].is_array()) {
      throw InputError(path, 0, "rules.speed_ratios: expected a list");
    }
    for (std::size_t i = 0; i < j["speed_ratios"].size(); ++i) {
      const json& s = j["speed_ratios"][i];
      const std::string where = "rules.speed_ratios[" + std::to_string(i) + "]";
      only_keys(s, {"name", "numerator", "denominator", "max_ratio", "max_relative_increase",
                    "alpha", "comment"}, path, where);
      SpeedRatioRule rule;
      read(s, "name", rule.name, path, where);
      read(s, "numerator", rule.numerator, path, where);
      read(s, "denominator", rule.denominator, path, where);
      double max_ratio = 0.0;
      if (s.contains("max_ratio")) {
        read(s, "max_ratio", max_ratio, path, where);
        rule.max_ratio = max_ratio;
      }
      read(s, "max_relative_increase", rule.max_relative_increase, path, where);
      read(s, "alpha", rule.alpha, path, where);
      if (rule.name.empty() || rule.numerator.empty() || rule.denominator.empty()) {
        throw InputError(path, 0, where + ": name, numerator and denominator are required");
      }
      if (!(rule.alpha > 0.0 && rule.alpha < 1.0)) {
        throw InputError(path, 0, where + ".alpha: expected a number in (0, 1)");
      }
      r.speed_ratios.push_back(rule);
    }
  }
  if (r.accuracy.empty() && r.speed_ratios.empty()) {
    throw InputError(path, 0,
                     "rules: \"accuracy\" is empty and there are no \"speed_ratios\": a gate with no rule "
                     "checks nothing (omit \"accuracy\" for the default rule \"*\")");
  }
  return r;
}

}  // namespace locbench::reports
