// Runs each slip/* experiment with 2 Monte-Carlo runs: result names and published tables.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <iostream>
#include <set>
#include <stdexcept>
#include <string>

#include "experiment_framework/experiment.h"
#include "pipelines/slip_sim.h"

namespace locbench::experiments {
namespace {

std::set<std::string> names(const reports::ExperimentResults& r) {
  std::set<std::string> s;
  for (const auto& m : r.results) s.insert(m.name());
  return s;
}

void dump(const reports::ExperimentResults& r) {
  if (!std::getenv("LOCBENCH_SLIP_VERBOSE")) return;
  for (const auto& m : r.results) {
    std::cout << m.name() << " mean " << m.summary.mean << " sd " << m.summary.stddev
              << (m.identifiable ? (*m.identifiable ? " identifiable" : " NOT identifiable") : "") << " " << m.note
              << "\n";
  }
  for (const auto& t : r.published) {
    std::cout << t.source << " / " << t.quantity << " [" << t.unit << "]\n";
    for (const auto& row : t.rows) {
      std::cout << "  " << row.label << ": published " << (row.published ? *row.published : NAN) << " ours "
                << (row.ours ? *row.ours : NAN) << "\n";
    }
  }
  for (const auto& n : r.notes) std::cout << "NOTE " << n << "\n";
}

// The registered experiment `name`; an exception (a failed test) when there is none.
const Experiment& registered(const char* name) {
  const Experiment* e = find_experiment(name);
  if (e == nullptr) throw std::runtime_error(std::string("no experiment ") + name);
  EXPECT_EQ(e->name(), name);
  return *e;
}

// `e` with 2 Monte-Carlo runs, printed with LOCBENCH_SLIP_VERBOSE.
reports::ExperimentResults run_two(const Experiment& e) {
  RunOptions o;
  o.seed = 11;
  o.runs = 2;
  auto r = e.run(e.default_config(), o);
  dump(r);
  return r;
}

TEST(SlipExperiments, NormalityTable31) {
  const Experiment& e = registered("slip/normality_table_3_1");
  const auto r = run_two(e);
  EXPECT_EQ(r.experiment, e.name());
  ASSERT_EQ(r.published.size(), 1u);
  EXPECT_EQ(r.published[0].source, "thesis Table 3.1");
  EXPECT_EQ(r.published[0].rows.size(), 9u);
  for (const auto& row : r.published[0].rows) {
    ASSERT_TRUE(row.published && row.ours) << row.label;
  }
  EXPECT_FALSE(r.published[0].note.empty());
  EXPECT_TRUE(names(r).contains("skewness_kurtosis_test/thesis_table_3_1/u2"));
}

TEST(SlipExperiments, CompassEkfTable32) {
  const Experiment& e = registered("slip/compass_ekf_table_3_2");
  EXPECT_EQ(e.default_config().at("runs"), 10);
  const auto r = run_two(e);
  EXPECT_EQ(r.seeds.size(), 2u);
  const auto n = names(r);
  for (const char* want : {"ekf_no_slip_correction/sim_corridor/final_position_error",
                           "ekf_slip_correction/sim_corridor/final_position_error",
                           "slip_detector/sim_corridor/precision", "slip_detector/sim_corridor/recall",
                           "ekf_slip_correction_latched_gyro/sim_corridor_disturbed/final_position_error"}) {
    EXPECT_TRUE(n.contains(want)) << want;
  }
  ASSERT_EQ(r.published.size(), 2u);
  EXPECT_EQ(r.published[0].source, "thesis Table 3.2");
  EXPECT_EQ(r.published[0].rows.size(), 11u);
  EXPECT_TRUE(r.published[0].rows[0].ours.has_value());
  EXPECT_FALSE(r.published[0].rows[5].ours.has_value());  // only 2 runs
}

TEST(SlipExperiments, IndirectKfTables3334) {
  const Experiment& e = registered("slip/indirect_kf_tables_3_3_3_4");
  const auto r = run_two(e);
  ASSERT_GE(r.published.size(), 2u);
  EXPECT_EQ(r.published[0].source, "thesis Table 3.3");
  EXPECT_EQ(r.published[1].source, "thesis Table 3.4");
  bool saw_db = false;
  for (const auto& m : r.results) {
    if (m.method == "ikf_heading_only" && m.variant == "dB") {
      saw_db = true;
      ASSERT_TRUE(m.identifiable.has_value());
      EXPECT_FALSE(*m.identifiable);
      EXPECT_FALSE(m.note.empty());
    }
  }
  EXPECT_TRUE(saw_db);
}

// Table 3.4 re-runs the EKF under models that need every run's estimates: the records carry each
// run's ticks, so that second pass simulates nothing, on any number of threads.
TEST(SlipExperiments, IndirectKfSimulatesEachRunOnce) {
  const Experiment* e = find_experiment("slip/indirect_kf_tables_3_3_3_4");
  ASSERT_NE(e, nullptr);
  const nlohmann::json config = merge_config(e->default_config(), {{"calibration_runs", 1}});
  RunOptions o;
  o.seed = 11;
  o.runs = 3;
  o.threads = 2;
  const std::size_t before = slip_sim::simulations;
  const auto r = e->run(config, o);
  EXPECT_EQ(slip_sim::simulations - before, 3u + 1u);  // the runs and the calibration run
  ASSERT_GE(r.published.size(), 2u);
}

// The full default configuration (10 runs), only when LOCBENCH_SLIP_FULL is set (for the
// README figures): LOCBENCH_SLIP_FULL=1 LOCBENCH_SLIP_VERBOSE=1 slip_experiments_test.
TEST(SlipExperiments, FullDefaultsWhenRequested) {
  if (!std::getenv("LOCBENCH_SLIP_FULL")) GTEST_SKIP() << "set LOCBENCH_SLIP_FULL to run";
  for (const char* name : {"slip/compass_ekf_table_3_2", "slip/indirect_kf_tables_3_3_3_4"}) {
    const Experiment* e = find_experiment(name);
    ASSERT_NE(e, nullptr);
    RunOptions o;
    o.seed = 1;
    dump(e->run(e->default_config(), o));
  }
}

}  // namespace
}  // namespace locbench::experiments
