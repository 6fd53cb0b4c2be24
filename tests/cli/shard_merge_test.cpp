// `locbench run --shard K/N` + `locbench merge`, and the batch-system recipes in docs/: merged
// shards equal a single-machine run, field by field; shards that do not belong together are
// refused with exit code 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "reports/schema_validation.h"
#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

using testing::Outcome;
using testing::read_json;
using testing::run_locbench;
using testing::run_shell;

// Every field of the experiment's part of two reports, compared exactly (context excluded:
// times, hosts, threads and command lines differ by design).
void expect_same_results(const std::filesystem::path& a, const std::filesystem::path& b) {
  const nlohmann::json x = read_json(a.string());
  const nlohmann::json y = read_json(b.string());
  for (const char* key : {"experiment", "seeds", "datasets", "configuration", "published", "cases", "notes", "plots"}) {
    EXPECT_EQ(x.value(key, nlohmann::json()), y.value(key, nlohmann::json())) << key << " of " << a;
  }
  ASSERT_EQ(x["results"].size(), y["results"].size()) << a;
  ASSERT_FALSE(x["results"].empty());
  for (std::size_t i = 0; i < x["results"].size(); ++i) {
    for (const auto& [field, value] : x["results"][i].items()) {
      EXPECT_EQ(value, y["results"][i][field]) << x["results"][i]["name"] << "." << field;
    }
  }
}

class ShardMerge : public ::testing::Test {
 protected:
  testing::ScratchDir dir;
  std::string at(const std::string& p) const { return (dir.path() / p).string(); }
  // Shards K = 1…n of `what` into shards/K.
  void make_shards(const std::string& what, int n, const std::string& extra = "") {
    for (int k = 1; k <= n; ++k) {
      const Outcome o = run_locbench("run " + what + " --shard " + std::to_string(k) + "/" + std::to_string(n) + " " +
                                     extra + " --out " + at("shards/" + std::to_string(k)));
      ASSERT_EQ(o.exit_code, 0) << o.output;
    }
  }
};

TEST_F(ShardMerge, ThreeShardsOfTwoExperimentsMergeToExactlyTheSingleMachineReports) {
  const std::string what = "odometry/sim_corridor noise/tables_4_1_4_2 --runs 5 --seed 9";
  make_shards(what, 3, "--threads 2");
  const Outcome m = run_locbench("merge " + at("shards") + " -o " + at("merged"));
  ASSERT_EQ(m.exit_code, 0) << m.output;
  ASSERT_EQ(run_locbench("run " + what + " --threads 1 --out " + at("single")).exit_code, 0);
  for (const char* e : {"odometry/sim_corridor.json", "noise/tables_4_1_4_2.json"}) {
    expect_same_results(at(std::string("merged/") + e), at(std::string("single/") + e));
    const nlohmann::json merged = read_json(at(std::string("merged/") + e));
    EXPECT_EQ(merged["context"]["shards"], 3);
    EXPECT_TRUE(reports::validate_report_json(merged).empty());
  }
  // One run id per invocation: the merge's in both merged reports, the single run's in both of its
  // own, each shard's its own, so each folder a gate reads is one run.
  const auto run_id = [&](const std::string& f) { return read_json(at(f))["context"]["run_id"].get<std::string>(); };
  EXPECT_EQ(run_id("merged/odometry/sim_corridor.json"), run_id("merged/noise/tables_4_1_4_2.json"));
  EXPECT_EQ(run_id("single/odometry/sim_corridor.json"), run_id("single/noise/tables_4_1_4_2.json"));
  EXPECT_NE(run_id("merged/odometry/sim_corridor.json"), run_id("single/odometry/sim_corridor.json"));
  EXPECT_EQ(run_id("shards/1/odometry/sim_corridor.shard-1-of-3.json"),
            run_id("shards/1/noise/tables_4_1_4_2.shard-1-of-3.json"));
  const Outcome gate = run_locbench("gate " + at("merged") + " --baseline " + at("single"));
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  // Shard 2 of 3 holds runs 1 and 4 of 0…4.
  const nlohmann::json s2 = read_json(at("shards/2/odometry/sim_corridor.shard-2-of-3.json"));
  EXPECT_TRUE(reports::validate_shard_json(s2).empty());
  ASSERT_EQ(s2["records"].size(), 2u);
  EXPECT_EQ(s2["records"][0]["task"], 1);
  EXPECT_EQ(s2["records"][1]["task"], 4);
}

TEST_F(ShardMerge, AnExperimentWithoutMonteCarloRunsRunsWholeInShardOne) {
  make_shards("slip/normality_table_3_1", 2);
  EXPECT_EQ(read_json(at("shards/1/slip/normality_table_3_1.shard-1-of-2.json"))["records"].size(), 1u);
  EXPECT_EQ(read_json(at("shards/2/slip/normality_table_3_1.shard-2-of-2.json"))["records"].size(), 0u);
  ASSERT_EQ(run_locbench("merge " + at("shards") + " -o " + at("merged.json")).exit_code, 0);
  ASSERT_EQ(run_locbench("run slip/normality_table_3_1 --out " + at("single")).exit_code, 0);
  expect_same_results(at("merged.json"), at("single/slip/normality_table_3_1.json"));
}

// Each way two shards can fail to belong together: exit code 2 and a message saying which.
TEST_F(ShardMerge, RefusesShardsThatDoNotBelongTogether) {
  const std::string what = "odometry/sim_corridor --runs 3 --seed 1";
  make_shards(what, 2);
  const std::string one = at("shards/1/odometry/sim_corridor.shard-1-of-2.json");
  const std::string two = at("shards/2/odometry/sim_corridor.shard-2-of-2.json");
  const auto expect_refused = [&](const std::string& inputs, const std::string& says) {
    const Outcome o = run_locbench("merge " + inputs + " -o " + at("m.json"));
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(says), std::string::npos) << says << " not in: " << o.output;
  };
  expect_refused(one, "shard 2/2 is missing");
  expect_refused(one + " " + one, "given twice");
  const auto other = [&](const std::string& name, const std::string& args) {
    const Outcome o = run_locbench("run odometry/sim_corridor " + args + " --shard 2/2 --out " + at(name));
    EXPECT_EQ(o.exit_code, 0) << o.output;
    return at(name + "/odometry/sim_corridor.shard-2-of-2.json");
  };
  expect_refused(one + " " + other("seed", "--runs 3 --seed 2"), "seed differs");
  expect_refused(one + " " + other("runs", "--runs 4 --seed 1"), "--runs differs");
  expect_refused(one + " " + other("config", "--runs 3 --seed 1 --set scenario.slip.straight.rate=0"),
                 "configuration differs");
  {
    nlohmann::json j = read_json(two);
    j["context"]["git_revision"] = "0123456789ab";
    std::ofstream(at("rev.json")) << j.dump();
  }
  expect_refused(one + " " + at("rev.json"), "git revision differs");
  {
    nlohmann::json j = read_json(two);
    j["shard"]["count"] = 3;
    std::ofstream(at("count.json")) << j.dump();
  }
  expect_refused(one + " " + at("count.json"), "shard count N differs");
  const Outcome noise = run_locbench("run noise/tables_4_1_4_2 --runs 1 --shard 2/2 --out " + at("noise"));
  ASSERT_EQ(noise.exit_code, 0) << noise.output;
  expect_refused(one + " " + at("noise/noise/tables_4_1_4_2.shard-2-of-2.json"), "-o must be a folder");
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 1 --out " + at("full")).exit_code, 0);
  expect_refused(at("full/odometry/sim_corridor.json"), "a full report, not a shard report");
}

TEST_F(ShardMerge, RunRejectsAShardOutsideOneToN) {
  for (const char* bad : {"3/2", "0/2", "1-2"}) {
    const Outcome o =
        run_locbench(std::string("run odometry/sim_corridor --runs 1 --shard ") + bad + " --out " + at("x"));
    EXPECT_EQ(o.exit_code, 2) << bad << ": " << o.output;
  }
}

TEST_F(ShardMerge, RunRecordsItsThreadCountInTheContextButNotInTheResults) {
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 3 --threads 2 --out " + at("t2")).exit_code, 0);
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 3 --threads 1 --out " + at("t1")).exit_code, 0);
  EXPECT_EQ(read_json(at("t2/odometry/sim_corridor.json"))["context"]["threads"], 2);
  expect_same_results(at("t2/odometry/sim_corridor.json"), at("t1/odometry/sim_corridor.json"));
}

// docs/slurm_array.sh run three times with the variables Slurm sets for an array task (here an
// array numbered from 0, --array=0-2), then merged.
TEST_F(ShardMerge, TheSlurmArrayRecipeMergesToTheSingleMachineReport) {
  const std::string script = std::string(LOCBENCH_SOURCE_DIR) + "/docs/slurm_array.sh";
  for (int id = 0; id < 3; ++id) {
    const Outcome o =
        run_shell("SLURM_ARRAY_TASK_ID=" + std::to_string(id) +
                  " SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=0 SLURM_CPUS_PER_TASK=2 LOCBENCH=" + LOCBENCH_EXE +
                  " EXPERIMENTS=odometry/sim_corridor RUNS=4 SEED=5 SHARD_DIR=" + at("shards") + " bash " + script);
    ASSERT_EQ(o.exit_code, 0) << o.output;
  }
  EXPECT_TRUE(std::filesystem::exists(at("shards/3/odometry/sim_corridor.shard-3-of-3.json")));
  ASSERT_EQ(run_locbench("merge " + at("shards") + " -o " + at("merged")).exit_code, 0);
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 4 --seed 5 --out " + at("single")).exit_code, 0);
  expect_same_results(at("merged/odometry/sim_corridor.json"), at("single/odometry/sim_corridor.json"));
  // Outside an array job the script says how to submit it.
  const Outcome bare = run_shell("env -u SLURM_ARRAY_TASK_ID bash " + script);
  EXPECT_NE(bare.exit_code, 0);
  EXPECT_NE(bare.output.find("sbatch --array"), std::string::npos) << bare.output;
}

// docs/gnu_parallel.sh with GNU parallel, and with its xargs fallback.
TEST_F(ShardMerge, TheGnuParallelRecipeMergesToTheSingleMachineReport) {
  const std::string script = std::string(LOCBENCH_SOURCE_DIR) + "/docs/gnu_parallel.sh";
  ASSERT_EQ(run_locbench("run odometry/sim_corridor --runs 4 --seed 3 --out " + at("single")).exit_code, 0);
  const bool have_parallel = run_shell("command -v parallel").exit_code == 0;
  for (const std::string fallback : {"", "1"}) {
    if (fallback.empty() && !have_parallel) {
      ADD_FAILURE() << "GNU parallel not installed (scripts/setup.sh installs it)";
      continue;
    }
    const std::string tag = fallback.empty() ? "parallel" : "xargs";
    const Outcome o =
        run_shell("LOCBENCH_NO_PARALLEL=" + fallback + " LOCBENCH=" + LOCBENCH_EXE +
                  " N=3 EXPERIMENTS=odometry/sim_corridor RUNS=4 SEED=3 SHARD_DIR=" + at(tag + "/shards") +
                  " OUT=" + at(tag + "/merged") + " bash " + script + " < /dev/null");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(o.output.find("xargs -P") != std::string::npos, !fallback.empty()) << o.output;
    expect_same_results(at(tag + "/merged/odometry/sim_corridor.json"), at("single/odometry/sim_corridor.json"));
  }
}

}  // namespace
}  // namespace locbench
