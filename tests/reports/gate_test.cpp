#include "reports/gate.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "reports/report_json.h"
#include "tests/reports/sample_report.h"
#include "tests/test_data.h"

namespace locbench::reports {
namespace {

const char* kKey = "odometry/sim_corridor:odometry_nominal/sim_corridor/final_position_error";

GateInput from_report(const Report& r, const testing::ScratchDir& dir, const std::string& name) {
  write_report(r, dir.file(name));
  return load_gate_input({dir.file(name).string()});
}

// Replaces the sample report's values (n = 3) by `values`.
Report with_values(std::vector<double> values) {
  Report r = testing::sample_report();
  r.body.results.clear();
  r.body.results.push_back(
      make_metric("odometry_nominal", "sim_corridor", "final_position_error", "m", "monte_carlo_runs", values));
  return r;
}

const GateRow& row(const GateVerdict& v, const std::string& key) {
  for (const GateRow& r : v.rows) {
    if (r.key == key) return r;
  }
  throw std::runtime_error("no row " + key);
}

TEST(Gate, TheBaselineAgainstItselfPasses) {
  testing::ScratchDir dir;
  const GateInput base = from_report(with_values({0.10, 0.12, 0.08}), dir, "a.json");
  const GateVerdict v = evaluate_gate(base, base, default_gate_rules());
  EXPECT_TRUE(v.passed());
  EXPECT_EQ(row(v, kKey).status, "ok");
  EXPECT_NEAR(*v.geomean_ratio, 1.0, 1e-12);
}

TEST(Gate, ADeliberatelyWorsenedResultFails) {
  testing::ScratchDir dir;
  // Baseline mean 0.10 m, 95% interval 0.10 ± 4.303·0.02/√3 = [0.050, 0.150].
  const GateInput base = from_report(with_values({0.10, 0.12, 0.08}), dir, "a.json");
  const GateInput worse = from_report(with_values({0.20, 0.22, 0.18}), dir, "b.json");
  const GateVerdict v = evaluate_gate(base, worse, default_gate_rules());
  EXPECT_FALSE(v.passed());
  EXPECT_EQ(row(v, kKey).status, "regressed");
  EXPECT_NEAR(*row(v, kKey).relative_change, 1.0, 1e-12);  // +100%
}

TEST(Gate, AWorseningInsideTheBaselinesIntervalIsNotARegression) {
  testing::ScratchDir dir;
  const GateInput base = from_report(with_values({0.10, 0.12, 0.08}), dir, "a.json");
  const GateInput slightly = from_report(with_values({0.13, 0.15, 0.11}), dir, "b.json");  // 0.13
  EXPECT_TRUE(evaluate_gate(base, slightly, default_gate_rules()).passed());
  GateRules strict = default_gate_rules();
  strict.accuracy[0].outside_interval = false;  // 30% > 5%: fails without the interval
  EXPECT_FALSE(evaluate_gate(base, slightly, strict).passed());
}

TEST(Gate, HigherIsBetterResultsRegressWhenTheyFall) {
  testing::ScratchDir dir;
  Report a = with_values({0.9, 0.9, 0.9});
  a.body.results[0].better = "higher";
  Report b = with_values({0.5, 0.5, 0.5});
  b.body.results[0].better = "higher";
  const GateVerdict v =
      evaluate_gate(from_report(a, dir, "a.json"), from_report(b, dir, "b.json"), default_gate_rules());
  EXPECT_EQ(row(v, kKey).status, "regressed");
}

TEST(Gate, AMissingResultFailsUnlessItsDatasetWasSkipped) {
  testing::ScratchDir dir;
  const GateInput base = from_report(with_values({0.1, 0.1, 0.1}), dir, "a.json");
  Report none = testing::sample_report();
  none.body.results.clear();
  const GateVerdict missing = evaluate_gate(base, from_report(none, dir, "b.json"), default_gate_rules());
  EXPECT_FALSE(missing.passed());
  EXPECT_EQ(row(missing, kKey).status, "missing");
}

// One Google Benchmark row: a repetition of `name` that took `us` µs.
nlohmann::json bench_row(const std::string& name, double us) {
  return {{"name", name},    {"run_name", name}, {"run_type", "iteration"},
          {"real_time", us}, {"cpu_time", us},   {"time_unit", "us"}};
}

// Google Benchmark JSON with `reps` repetitions of two kernels.
void write_bench(const std::filesystem::path& p, const std::vector<double>& fast, const std::vector<double>& slow) {
  nlohmann::json j = {{"context", {{"library_build_type", "release"}}}, {"benchmarks", nlohmann::json::array()}};
  for (std::size_t i = 0; i < fast.size(); ++i) {
    j["benchmarks"].push_back(bench_row("BM_Fast", fast[i]));
    j["benchmarks"].push_back(bench_row("BM_Slow", slow[i]));
  }
  std::ofstream(p) << j.dump();
}

GateRules ratio_rules() {
  GateRules r = default_gate_rules();
  r.speed_ratios.push_back({"fast_vs_slow", "bench:BM_Fast", "bench:BM_Slow", 0.8, 0.10, 0.05});
  return r;
}

// The ratio rule's verdict on a baseline and a current run, given BM_Fast's times [µs] in each
// repetition; BM_Slow takes 100 µs in every one.
GateVerdict ratio_verdict(const std::vector<double>& base_fast, const std::vector<double>& now_fast) {
  testing::ScratchDir dir;
  write_bench(dir.file("base.json"), base_fast, std::vector<double>(base_fast.size(), 100.0));
  write_bench(dir.file("now.json"), now_fast, std::vector<double>(now_fast.size(), 100.0));
  return evaluate_gate(load_gate_input({dir.file("base.json").string()}),
                       load_gate_input({dir.file("now.json").string()}), ratio_rules());
}

TEST(Gate, ASpeedRatioThatGrowsSignificantlyFails) {
  // Baseline ratio ≈ 0.5 over 6 repetitions; now ≈ 0.7 in every repetition.
  const GateVerdict v = ratio_verdict({50, 51, 49, 50, 52, 48}, {70, 71, 69, 70, 72, 68});
  ASSERT_EQ(v.ratios.size(), 1u);
  EXPECT_EQ(v.ratios[0].status, "regressed");
  EXPECT_NEAR(*v.ratios[0].old_ratio, 0.5, 1e-12);
  EXPECT_NEAR(*v.ratios[0].new_ratio, 0.7, 1e-12);
  EXPECT_LT(*v.ratios[0].p_value, 0.01);
  // Raw times are shown, never gated by themselves.
  EXPECT_EQ(row(v, "bench:BM_Fast").status, "info");
}

TEST(Gate, ARatioChangeThatIsNoiseIsNotARegression) {
  // Both runs scatter between 0.40 and 0.62: medians 0.525 and 0.595 (+13%, above the 10%
  // tolerance), but the samples overlap too much for the change to be significant.
  const GateVerdict v = ratio_verdict({40, 60, 45, 55, 50, 58}, {42, 62, 61, 59, 44, 60});
  EXPECT_NEAR(*v.ratios[0].relative_change, 0.595 / 0.525 - 1.0, 1e-12);
  EXPECT_EQ(v.ratios[0].status, "ok") << v.ratios[0].detail;
  EXPECT_GT(*v.ratios[0].p_value, 0.05);
}

TEST(Gate, ARatioAboveItsCeilingFailsEvenWithoutABaseline) {
  testing::ScratchDir dir;
  write_bench(dir.file("now.json"), {90}, {100});
  GateInput empty;
  const GateVerdict v = evaluate_gate(empty, load_gate_input({dir.file("now.json").string()}), ratio_rules());
  EXPECT_EQ(v.ratios[0].status, "regressed");  // 0.9 > ceiling 0.8
}

TEST(Gate, ARatioWhoseBenchmarkSkippedForMissingDataFails) {
  testing::ScratchDir dir;
  write_bench(dir.file("base.json"), {50, 51}, {100, 100});
  // BM_Fast skipped (SkipWithError, as the real-scan kernels do without LOCBENCH_DATA): Google
  // Benchmark still writes a row, with error_occurred and a zero time.
  nlohmann::json j = {{"benchmarks", nlohmann::json::array()}};
  nlohmann::json skipped = bench_row("BM_Fast", 0.0);
  skipped["error_occurred"] = true;
  skipped["error_message"] = "intel log not found";
  j["benchmarks"].push_back(skipped);
  j["benchmarks"].push_back(bench_row("BM_Slow", 100.0));
  std::ofstream(dir.file("now.json")) << j.dump();
  const GateVerdict v = evaluate_gate(load_gate_input({dir.file("base.json").string()}),
                                      load_gate_input({dir.file("now.json").string()}), ratio_rules());
  ASSERT_EQ(v.ratios.size(), 1u);
  EXPECT_EQ(v.ratios[0].status, "missing") << v.ratios[0].detail;
  EXPECT_FALSE(v.passed());
}

TEST(GateRules, RejectAnUnknownKeyByItsPath) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("r.json")) << R"({"accuracy": [{"match": "*", "max_relativ": 0.1}]})";
  try {
    load_gate_rules(dir.file("r.json").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rules.accuracy[0].max_relativ: unknown key (expected one of: "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("max_relative_worsening"), std::string::npos) << e.what();
  }
}

TEST(GateRules, RejectAWrongTypeAndAnOutOfRangeValueByTheirPathAndFile) {
  testing::ScratchDir dir;
  const auto message = [&](const std::string& text) {
    std::ofstream(dir.file("r.json")) << text;
    try {
      load_gate_rules(dir.file("r.json").string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = dir.file("r.json").string();
  EXPECT_EQ(message(R"({"accuracy": [{"max_relative_worsening": "5%"}]})"),
            file + ": rules.accuracy[0].max_relative_worsening: expected a number, found string");
  EXPECT_EQ(message(R"({"speed_ratios": [{"name": "a", "numerator": "b", "denominator": "c", "alpha": 2}]})"),
            file + ": rules.speed_ratios[0].alpha: expected a number in (0, 1)");
  EXPECT_EQ(message(R"({"fail_on_missing": 1})"),
            file + ": rules.fail_on_missing: expected true or false, found number");
}

TEST(GateInput, RejectsJsonThatIsNeitherAReportNorABenchmark) {
  testing::ScratchDir dir;
  std::ofstream(dir.file("x.json")) << R"({"hello": 1})";
  EXPECT_THROW(load_gate_input({dir.file("x.json").string()}), InputError);
  EXPECT_THROW(load_gate_input({dir.file("absent.json").string()}), InputError);
}

TEST(GateOutput, MarkdownAndJsonCarryTheVerdict) {
  testing::ScratchDir dir;
  const GateInput base = from_report(with_values({0.10, 0.12, 0.08}), dir, "a.json");
  const GateInput worse = from_report(with_values({0.20, 0.22, 0.18}), dir, "b.json");
  const GateVerdict v = evaluate_gate(base, worse, default_gate_rules());
  EXPECT_NE(gate_markdown(v).find("failed"), std::string::npos);
  EXPECT_NE(gate_table(v).find("gate: FAILED"), std::string::npos);
  const nlohmann::json j = gate_json(v, base, worse);
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["schema"], "locbench.gate/1");
}

}  // namespace
}  // namespace locbench::reports

namespace locbench::reports {
namespace {

TEST(Gate, SignedErrorsAreJudgedByTheirDistanceFromZeroAndEstimatesByAnyChange) {
  GateSeries base;
  base.key = "x:m/d/E_d_error";
  base.value = -0.001;
  base.n = 1;
  GateInput a, b;
  base.better = "closer_to_zero";
  a.series[base.key] = base;
  GateSeries now = base;
  now.value = -0.003;  // lower, but three times further from zero
  b.series[base.key] = now;
  EXPECT_FALSE(evaluate_gate(a, b, default_gate_rules()).passed());
  base.better = now.better = "stable";
  a.series[base.key] = base;
  now.value = -0.00099;  // 1% change: inside the 5% tolerance
  b.series[base.key] = now;
  EXPECT_TRUE(evaluate_gate(a, b, default_gate_rules()).passed());
  now.value = -0.0009;  // 10% change in either direction fails
  b.series[base.key] = now;
  EXPECT_FALSE(evaluate_gate(a, b, default_gate_rules()).passed());
}

}  // namespace
}  // namespace locbench::reports
