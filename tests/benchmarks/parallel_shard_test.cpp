// Monte-Carlo experiments give the same report for any thread count and when run as shards and
// merged (the records pass through the shard file's JSON text, as on a batch system).
#include <gtest/gtest.h>

#include "core/errors.h"
#include "experiment_framework/experiment.h"
#include "experiment_framework/shard.h"
#include "reports/report_json.h"
#include "reports/shard_report.h"

namespace locbench::experiments {
namespace {

struct Case {
  const char* experiment;
  int runs;
  nlohmann::json overrides;
};

// The experiments with different structures: one task per run (corridor, chapter-4 tables),
// runs × resolutions (sweep) or × cases (identifiability), shared calibration runs in the setup (compass EKF), and a
// summary step that needs every run's records and re-runs in parallel (indirect KF). Kept small.
const Case kCases[] = {
    {"odometry/sim_corridor", 4, nlohmann::json::object()},
    {"noise/tables_4_1_4_2", 3, nlohmann::json::object()},
    {"noise/encoder_resolution_sweep", 2, {{"meters_per_tick", {0.001, 0.01264}}}},
    {"slip/compass_ekf_table_3_2", 3, {{"calibration_runs", 1}}},
    {"slip/indirect_kf_tables_3_3_3_4", 3, {{"calibration_runs", 1}}},
    // runs × cases with its own seed numbering, (case + 1)·1000 + run.
    {"calibration/identifiability",
     1,
     {{"cases",
       {{{"name", "E_d_1.005"}, {"E_d", 1.005}, {"E_b", 1.0}, {"E_o", 1.0}},
        {{"name", "all"}, {"E_d", 1.005}, {"E_b", 1.02}, {"E_o", 0.99}}}}}},
};

class ParallelAndShards : public ::testing::TestWithParam<Case> {
 protected:
  const Experiment& experiment() const {
    const Experiment* e = find_experiment(GetParam().experiment);
    if (!e) throw std::runtime_error(std::string("no experiment ") + GetParam().experiment);
    return *e;
  }
  nlohmann::json config() const { return merge_config(experiment().default_config(), GetParam().overrides); }
  RunOptions options(int threads) const {
    RunOptions o;
    o.seed = 17;
    o.runs = GetParam().runs;
    o.threads = threads;
    return o;
  }
};

TEST_P(ParallelAndShards, OneAndThreeThreadsGiveIdenticalResults) {
  const nlohmann::json one = reports::results_to_json(experiment().run(config(), options(1)));
  const nlohmann::json three = reports::results_to_json(experiment().run(config(), options(3)));
  EXPECT_EQ(one, three);
  EXPECT_FALSE(one["results"].empty());
}

TEST_P(ParallelAndShards, ThreeShardsMergedWriteTheSingleRunsReportByteForByte) {
  const Experiment& e = experiment();
  const nlohmann::json single = reports::results_to_json(e.run(config(), options(1)));
  const int tasks = e.task_count(config(), options(1));
  ASSERT_GT(tasks, 1);
  std::vector<nlohmann::json> records(static_cast<std::size_t>(tasks));
  for (int k = 1; k <= 3; ++k) {
    const std::vector<int> mine = shard_tasks({k, 3}, tasks);
    reports::ShardReport s;
    s.experiment = e.name();
    s.tasks = tasks;
    const auto got = e.run_tasks(config(), options(2), mine);
    for (std::size_t i = 0; i < mine.size(); ++i) s.records.push_back({mine[i], got[i]});
    // Through the file's text and back.
    const auto back = reports::shard_report_from_json(nlohmann::json::parse(reports::to_json(s).dump()), "shard");
    for (const auto& r : back.records) records[static_cast<std::size_t>(r.task)] = r.record;
  }
  const nlohmann::json merged = reports::results_to_json(e.summarise_records(config(), options(1), records));
  // The single run summarises its records as built, the merge as read back from the shards' text:
  // the same report, byte for byte.
  EXPECT_EQ(merged.dump(), single.dump());
}

INSTANTIATE_TEST_SUITE_P(MonteCarlo, ParallelAndShards, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           std::string n = i.param.experiment;
                           for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

TEST(Tasks, AnExperimentWithoutMonteCarloRunsIsOneTaskWhoseRecordRebuildsItExactly) {
  const Experiment* e = find_experiment("slip/normality_table_3_1");
  ASSERT_NE(e, nullptr);
  const nlohmann::json config = e->default_config();
  const RunOptions o;
  EXPECT_EQ(e->task_count(config, o), 1);
  EXPECT_EQ(shard_tasks({1, 3}, 1), (std::vector<int>{0}));
  EXPECT_TRUE(shard_tasks({2, 3}, 1).empty());
  const auto records = e->run_tasks(config, o, {0});
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(reports::results_to_json(e->summarise_records(config, o, records)),
            reports::results_to_json(e->run(config, o)));
}

TEST(Tasks, ASummaryOfTooFewRecordsIsRefused) {
  const Experiment* e = find_experiment("odometry/sim_corridor");
  RunOptions o;
  o.runs = 3;
  const auto records = e->run_tasks(e->default_config(), o, {0, 1});
  EXPECT_THROW(e->summarise_records(e->default_config(), o, records), UsageError);
  EXPECT_THROW(e->run_tasks(e->default_config(), o, {3}), UsageError);
}

}  // namespace
}  // namespace locbench::experiments
