// The gate fails closed: one test per way a gate was fooled into passing.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include "reports/gate.h"
#include "reports/gate_checks.h"
#include "reports/report_json.h"
#include "tests/reports/sample_report.h"
#include "tests/test_data.h"

namespace locbench::reports {
namespace {

GateInput load(const Report& r, const testing::ScratchDir& dir, const std::string& name) {
  write_report(r, dir.file(name));
  return load_gate_input({dir.file(name).string()});
}

const GateRow* find_row(const GateVerdict& v, const std::string& key) {
  for (const GateRow& r : v.rows) {
    if (r.key == key) return &r;
  }
  return nullptr;
}

// odometry/real_logs on two recorded logs, aces and intel, final position errors over 3 runs.
Report real_logs_report() {
  Report r = testing::sample_report();
  r.body.experiment = "odometry/real_logs";
  r.body.cases.clear();
  r.body.datasets = {{"aces", "/data/slam_benchmark/clf/aces.from_bag.clf.gz", "crc32:00000001", 100, 10.0},
                     {"intel", "/data/slam_benchmark/clf/intel.from_bag.clf.gz", "crc32:00000002", 100, 10.0}};
  r.body.results.clear();
  for (const char* ds : {"aces", "intel"}) {
    r.body.results.push_back(
        make_metric("odometry_nominal", ds, "final_position_error", "m", "runs", std::vector<double>{1.0, 1.2, 0.8}));
  }
  return r;
}

// The current run without aces: its results and its dataset gone, a "skipped" case added.
Report without_aces(const std::string& reason = "dataset not found at /ci/aces.clf.gz (set LOCBENCH_DATA)") {
  Report r = real_logs_report();
  r.body.results.erase(r.body.results.begin());
  r.body.datasets.erase(r.body.datasets.begin());
  r.body.cases.push_back({"odometry/aces", "skipped", reason});
  return r;
}

const std::string kAces = "odometry/real_logs:odometry_nominal/aces/final_position_error";

// The gate with the default rules on `now` against real_logs_report() as the baseline.
GateVerdict gate_against_real_logs(const Report& now, const testing::ScratchDir& dir) {
  return evaluate_gate(load(real_logs_report(), dir, "a.json"), load(now, dir, "b.json"), default_gate_rules());
}

// Google Benchmark JSON: BM_Fast and BM_Slow, one repetition each per entry.
std::string bench(const std::vector<double>& fast, const std::vector<double>& slow) {
  nlohmann::json j = {{"benchmarks", nlohmann::json::array()}};
  for (std::size_t i = 0; i < fast.size(); ++i) {
    for (const auto& [name, t] : {std::pair{"BM_Fast", fast[i]}, std::pair{"BM_Slow", slow[i]}}) {
      j["benchmarks"].push_back(
          {{"name", name}, {"run_name", name}, {"run_type", "iteration"}, {"real_time", t}, {"time_unit", "ns"}});
    }
  }
  return j.dump();
}

GateVerdict bench_verdict(const std::string& base, const std::string& now) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("base.json")) << base;
  std::ofstream(dir.file("now.json")) << now;
  GateRules rules = default_gate_rules();
  rules.speed_ratios.push_back({"fast_vs_slow", "bench:BM_Fast", "bench:BM_Slow", std::nullopt, 0.10, 0.05});
  return evaluate_gate(load_gate_input({dir.file("base.json").string()}),
                       load_gate_input({dir.file("now.json").string()}), rules);
}

TEST(GateFailClosed, AZeroOverZeroNanosecondSpeedPairFailsInsteadOfPassingAsNan) {
  const GateVerdict v = bench_verdict(bench({50, 51}, {100, 100}), bench({0, 0}, {0, 0}));
  ASSERT_EQ(v.ratios.size(), 1u);
  EXPECT_EQ(v.ratios[0].status, "invalid") << v.ratios[0].detail;
  EXPECT_FALSE(v.ratios[0].new_ratio.has_value());
  EXPECT_EQ(find_row(v, "bench:BM_Fast")->status, "invalid");
  EXPECT_FALSE(v.passed());
  EXPECT_NE(gate_table(v).find("≤ 0 ns"), std::string::npos) << gate_table(v);
}

TEST(GateFailClosed, NegativeTimesFailInsteadOfCountingAsImproved) {
  const GateVerdict v = bench_verdict(bench({50, 51}, {100, 100}), bench({-50, -51}, {100, 100}));
  EXPECT_EQ(v.ratios[0].status, "invalid");
  EXPECT_FALSE(v.passed());
  // A report's time (unit s, lower is better) below zero is no measurement either.
  testing::ScratchDir dir;
  Report a = real_logs_report(), b = real_logs_report();
  a.body.results[0] = make_metric("odometry_nominal", "aces", "runtime", "s", "runs", std::vector<double>{1, 1, 1});
  b.body.results[0] = make_metric("odometry_nominal", "aces", "runtime", "s", "runs", std::vector<double>{-1, -1, -1});
  const GateVerdict t = evaluate_gate(load(a, dir, "a.json"), load(b, dir, "b.json"), default_gate_rules());
  EXPECT_EQ(find_row(t, "odometry/real_logs:odometry_nominal/aces/runtime")->status, "invalid");
  EXPECT_FALSE(t.passed());
}

TEST(GateFailClosed, ANegativePositionErrorFailsInsteadOfPassingAsImproved) {
  testing::ScratchDir dir;
  Report now = real_logs_report();
  now.body.results[0] = make_metric("odometry_nominal", "aces", "final_position_error", "m", "runs",
                                    std::vector<double>{-1.0, -1.2, -0.8});
  const GateVerdict v = gate_against_real_logs(now, dir);
  EXPECT_EQ(find_row(v, kAces)->status, "invalid");
  EXPECT_NE(find_row(v, kAces)->detail.find("cannot be negative"), std::string::npos) << find_row(v, kAces)->detail;
  EXPECT_FALSE(v.passed());
}

TEST(GateFailClosed, SignedDifferencesAndSignedErrorsMayBeNegative) {
  GateSeries s;
  s.unit = "m";
  s.better = "lower";
  s.variant = "rpe_translation_minus_odometry";  // a difference of two errors
  s.value = -0.2;
  EXPECT_EQ(implausible(s), "");
  s.variant = "heading_error_after";
  s.better = "closer_to_zero";  // a signed error
  EXPECT_EQ(implausible(s), "");
  s.better = "lower";
  EXPECT_NE(implausible(s), "");
}

TEST(GateFailClosed, NonFiniteValuesFail) {
  GateInput a, b;
  GateSeries s;
  s.key = "x:m/d/final_position_error";
  s.unit = "m";
  s.value = 1.0;
  a.series[s.key] = s;
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    GateSeries now = s;
    now.value = bad;
    b.series[s.key] = now;
    const GateVerdict v = evaluate_gate(a, b, default_gate_rules());
    EXPECT_EQ(find_row(v, s.key)->status, "invalid");
    EXPECT_FALSE(v.passed());
  }
  GateSeries now = s;
  now.samples = {1.0, std::nan("")};
  now.n = 2;
  b.series[s.key] = now;
  EXPECT_FALSE(evaluate_gate(a, b, default_gate_rules()).passed());
}

TEST(GateFailClosed, ValuesThatContradictTheMeanMinMaxOrNFail) {
  testing::ScratchDir dir;
  const GateInput base = load(real_logs_report(), dir, "a.json");
  const auto verdict = [&](const std::function<void(MetricResult&)>& edit) {
    Report now = real_logs_report();
    edit(now.body.results[0]);
    return evaluate_gate(base, load(now, dir, "b.json"), default_gate_rules());
  };
  EXPECT_FALSE(verdict([](MetricResult& m) { m.summary.mean = 0.5; }).passed());  // values say 1.0
  EXPECT_FALSE(verdict([](MetricResult& m) { m.summary.n = 30; }).passed());
  EXPECT_FALSE(verdict([](MetricResult& m) { m.summary.min = 0.1; }).passed());
  EXPECT_FALSE(verdict([](MetricResult& m) { m.summary.max = 9.0; }).passed());
  const GateVerdict v = verdict([](MetricResult& m) { m.summary.mean = 0.5; });
  EXPECT_NE(find_row(v, kAces)->detail.find("contradicts its `values`"), std::string::npos);
  // Rounding of the recomputed mean is tolerated.
  EXPECT_TRUE(verdict([](MetricResult& m) { m.summary.mean *= 1.0 + 1e-14; }).passed());
}

TEST(GateFailClosed, DeletedResultsWithAnAddedSkippedCaseFailWhenTheReportStillListsTheDataset) {
  testing::ScratchDir dir;
  Report forged = real_logs_report();
  forged.body.results.erase(forged.body.results.begin());  // the dataset stays listed as read
  forged.body.cases.push_back({"odometry/aces", "skipped", "dataset not found at /x"});
  const GateVerdict v = gate_against_real_logs(forged, dir);
  EXPECT_EQ(find_row(v, kAces)->status, "missing");
  EXPECT_NE(find_row(v, kAces)->detail.find("skip not backed"), std::string::npos) << find_row(v, kAces)->detail;
  EXPECT_FALSE(v.passed());
}

TEST(GateFailClosed, ASkipWhoseReasonIsNotAbsentDataFails) {
  testing::ScratchDir dir;
  const GateVerdict v = gate_against_real_logs(without_aces("I did not feel like it"), dir);
  EXPECT_EQ(find_row(v, kAces)->status, "missing");
  EXPECT_FALSE(v.passed());
}

TEST(GateFailClosed, ASkipOfSimulatedDataFails) {
  testing::ScratchDir dir;
  Report base = testing::sample_report();  // sim/corridor, simulated
  base.body.results.resize(1);
  Report none = base;
  none.body.results.clear();
  none.body.datasets.clear();
  none.body.cases = {{"odometry/sim_corridor", "skipped", "dataset not found"}};
  const GateVerdict v = evaluate_gate(load(base, dir, "a.json"), load(none, dir, "b.json"), default_gate_rules());
  EXPECT_FALSE(v.passed());
}

TEST(GateFailClosed, ASkipBackedByProvenancePasses) {
  testing::ScratchDir dir;
  const GateVerdict v = gate_against_real_logs(without_aces(), dir);
  EXPECT_EQ(find_row(v, kAces)->status, "skipped");
  EXPECT_TRUE(v.passed()) << gate_table(v);
}

TEST(GateFailClosed, SkippingEveryRecordedDatasetFailsLikeSkipMissingAll) {
  testing::ScratchDir dir;
  Report none = without_aces();
  none.body.results.clear();
  none.body.datasets.clear();
  none.body.cases.push_back({"odometry/intel", "skipped", "dataset not found at /ci/intel.clf.gz"});
  const GateVerdict v = gate_against_real_logs(none, dir);
  EXPECT_EQ(find_row(v, kAces)->status, "skipped");
  ASSERT_NE(find_row(v, "recorded data"), nullptr) << gate_table(v);
  EXPECT_NE(find_row(v, "recorded data")->detail.find("none was compared"), std::string::npos);
  EXPECT_FALSE(v.passed());
}

TEST(GateFailClosed, CurrentReportsOfDifferentRunIdsFail) {
  testing::ScratchDir dir;
  Report a = real_logs_report(), b = testing::sample_report();
  a.provenance.run_id = "run-new";
  b.provenance.run_id = "run-old";  // written by an earlier run, left in the folder
  write_report(a, dir.path() / "cur" / "a.json");
  write_report(b, dir.path() / "cur" / "b.json");
  const GateInput current = load_gate_input({(dir.path() / "cur").string()});
  GateVerdict v = evaluate_gate(current, current, default_gate_rules());
  ASSERT_TRUE(v.passed());
  fail_mixed_runs(current, v);
  EXPECT_FALSE(v.passed());
  ASSERT_NE(find_row(v, "run id"), nullptr);
  EXPECT_EQ(find_row(v, "run id")->status, "mixed");
  EXPECT_EQ(gate_json(v, current, current)["passed"], false);
  // A report without a run id beside one with an id is mixed too.
  b.provenance.run_id = "";
  write_report(b, dir.path() / "cur" / "b.json");
  EXPECT_NE(mixed_run_ids(load_gate_input({(dir.path() / "cur").string()})), "");
}

TEST(GateFailClosed, ReportsOfOneRunIdOrOfNoneAreOneRun) {
  testing::ScratchDir dir;
  Report a = real_logs_report(), b = testing::sample_report();
  write_report(a, dir.path() / "old" / "a.json");  // made before run ids: one run
  write_report(b, dir.path() / "old" / "b.json");
  EXPECT_EQ(mixed_run_ids(load_gate_input({(dir.path() / "old").string()})), "");
  a.provenance.run_id = b.provenance.run_id = "20261127T041200Z-1-0000abcd";
  write_report(a, dir.path() / "new" / "a.json");
  write_report(b, dir.path() / "new" / "b.json");
  EXPECT_EQ(mixed_run_ids(load_gate_input({(dir.path() / "new").string()})), "");
}

}  // namespace
}  // namespace locbench::reports
