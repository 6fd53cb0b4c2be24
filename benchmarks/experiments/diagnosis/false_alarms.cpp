// Experiment diagnosis/false_alarms: the diagnosis on logs with nothing hidden, from both
// generators — the window-model one (datasets/diagnosis/hidden_effects.h, encoder and velocity
// odometry alternately) and the physical one (datasets/diagnosis/physical_log_generator.h: 10 Hz
// ODOM and TRUEPOS, a commanded robot at 1 kHz). A false alarm is any cause kept or any structure
// left unexplained; the goal is at most 1% per log. Each task is one log; `runs` (default 200)
// logs per generator.
#include <fmt/format.h>

#include <map>

#include "algorithms/diagnosis/diagnosis.h"
#include "datasets/diagnosis/hidden_effects.h"
#include "datasets/diagnosis/physical_log_generator.h"
#include "experiment_framework/monte_carlo.h"
#include "experiment_framework/registry.h"

namespace locbench::experiments::diagnosis_false_alarms {

const ExperimentInfo kInfo{
    .name = "diagnosis/false_alarms",
    .description =
        "False alarms of the diagnosis on logs with nothing hidden, from the window-model generator and from the "
        "physical generator (goal ≤ 1% per log)",
    .in_default_suite = false};  // 400 diagnoses; `locbench run diagnosis/false_alarms`

struct Options {
  int runs = 200;
  double false_alarm = 0.01;
  double physical_duration_s = 120.0;
};
template <class V>
void visit_fields(V& v, Options& o) {
  v.field("runs", o.runs, "", at_least(1), "logs per generator");
  v.field("false_alarm", o.false_alarm, "", open(0.0, 1.0), "false-alarm rate of each test");
  v.field("physical_duration_s", o.physical_duration_s, "s", closed(60.0, 3600.0),
          "length of each physical generator's log");
}

struct FalseAlarmSetup {
  nlohmann::json config;
  diagnosis::DiagnosisOptions options;
  double physical_duration = 120.0;
};

class DiagnosisFalseAlarms final : public MonteCarloExperiment<Options, FalseAlarmSetup> {
 public:
  FalseAlarmSetup setup(const Options& c, const McPlan&) const override {
    FalseAlarmSetup s;
    s.config = options_json(c);
    s.options.false_alarm = c.false_alarm;
    s.physical_duration = c.physical_duration_s;
    return s;
  }
  int tasks(const FalseAlarmSetup&, const McPlan& plan) const override { return 2 * plan.runs; }

  nlohmann::json run_task(const FalseAlarmSetup& s, const McPlan& plan, int task) const override {
    const bool physical = task >= plan.runs;
    Log log;
    if (physical) {
      sim::PhysicalOptions o;
      o.duration = s.physical_duration;
      log = sim::generate_physical_log({}, plan.run_seed(task), o);
    } else {
      sim::GeneratorOptions o;
      o.velocity_odometry = task % 2 == 1;
      log = sim::generate_log({}, plan.run_seed(task), o).log;
    }
    const auto d = diagnosis::diagnose_log(log, s.options);
    nlohmann::json r{{"generator", physical ? "physical" : "window_model"}, {"detected", d.detected}};
    r["unexplained"] = nlohmann::json::array();
    for (const auto& u : d.unexplained) r["unexplained"].push_back(u.test + ":" + u.residual);
    return r;
  }

  reports::ExperimentResults summarise(const FalseAlarmSetup& s, const McPlan& plan,
                                       const std::vector<nlohmann::json>& records) const override {
    reports::ExperimentResults out = start_results(s.config);
    for (int k = 0; k < static_cast<int>(records.size()); ++k) out.seeds.push_back(plan.run_seed(k));
    for (const char* generator : {"window_model", "physical"}) {
      std::vector<double> alarm;
      std::map<std::string, int> what;
      for (const auto& r : records) {
        if (r.at("generator") != generator) continue;
        const bool any = !r.at("detected").empty() || !r.at("unexplained").empty();
        alarm.push_back(any ? 1.0 : 0.0);
        for (const auto& id : r.at("detected")) ++what["kept " + id.get<std::string>()];
        for (const auto& id : r.at("unexplained")) ++what["unexplained " + id.get<std::string>()];
      }
      if (alarm.empty()) continue;
      out.results.push_back(reports::make_metric("diagnose", std::string(generator) + "_null_logs", "false_alarm_rate",
                                                 "", "logs", alarm));
      double n = 0.0;
      for (double a : alarm) n += a;
      std::string detail;
      for (const auto& [k, v] : what) detail += fmt::format("{}{} ×{}", detail.empty() ? "" : ", ", k, v);
      out.notes.push_back(fmt::format("{} generator: {} false alarm(s) in {} null logs ({:.2f}%; goal ≤ 1%){}",
                                      generator, n, alarm.size(), 100.0 * n / static_cast<double>(alarm.size()),
                                      detail.empty() ? "" : ": " + detail));
    }
    return out;
  }
};

const Registration<DiagnosisFalseAlarms> diagnosis_false_alarms_registration(kInfo);

}  // namespace locbench::experiments::diagnosis_false_alarms
