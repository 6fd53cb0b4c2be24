#include "experiment_framework/shard.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/errors.h"
#include "experiment_framework/parallel_tasks.h"

namespace locbench::experiments {
namespace {

TEST(ParseShard, ReadsKOfN) {
  const Shard s = parse_shard("2/8");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 8);
  EXPECT_EQ(parse_shard("1/1").count, 1);
}

TEST(ParseShard, RejectsAnythingButOneToNOfN) {
  for (const char* bad : {"0/3", "4/3", "3", "a/b", "2/0", "-1/3", "1/3x", "/3", ""}) {
    EXPECT_THROW(parse_shard(bad), UsageError) << bad;
  }
}

TEST(ShardTasks, TakesTheIndicesCongruentToKMinusOneModuloN) {
  EXPECT_EQ(shard_tasks({1, 3}, 7), (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(shard_tasks({2, 3}, 7), (std::vector<int>{1, 4}));
  EXPECT_EQ(shard_tasks({3, 3}, 7), (std::vector<int>{2, 5}));
  EXPECT_TRUE(shard_tasks({5, 5}, 3).empty());  // more shards than tasks: some are empty
}

TEST(ShardTasks, EveryTaskIsInExactlyOneShard) {
  for (int n = 1; n <= 6; ++n) {
    std::vector<int> seen(11, 0);
    for (int k = 1; k <= n; ++k) {
      for (int t : shard_tasks({k, n}, 11)) ++seen[static_cast<std::size_t>(t)];
    }
    for (int c : seen) EXPECT_EQ(c, 1) << "N = " << n;
  }
}

TEST(ParallelTasks, RunsEveryIndexOnceOnSeveralThreads) {
  std::vector<std::atomic<int>> hits(50);
  parallel_tasks(3, hits.size(), [&](std::size_t i) { ++hits[i]; });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(ParallelTasks, RethrowsTheErrorOfTheLowestFailingIndexWhateverTheSchedule) {
  for (int threads : {1, 3}) {
    std::atomic<int> ran{0};
    try {
      parallel_tasks(threads, 20, [&](std::size_t i) {
        ++ran;
        if (i == 7 || i == 13) throw std::runtime_error("task " + std::to_string(i));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 7");
    }
    EXPECT_EQ(ran.load(), 20);  // every task still ran
  }
}

TEST(ParallelTasks, TasksStartedInsideATaskEachRunOnceAndRethrowTheLowestError) {
  std::vector<std::vector<std::atomic<int>>> hits(4);
  for (auto& h : hits) h = std::vector<std::atomic<int>>(30);
  std::vector<std::string> errors(4);
  parallel_tasks(2, hits.size(), [&](std::size_t i) {
    try {
      parallel_tasks(8, hits[i].size(), [&](std::size_t k) {
        ++hits[i][k];
        if (k == 11 || k == 23) throw std::runtime_error("inner " + std::to_string(k));
      });
    } catch (const std::runtime_error& e) {
      errors[i] = e.what();
    }
  });
  for (std::size_t i = 0; i < hits.size(); ++i) {
    for (const auto& h : hits[i]) EXPECT_EQ(h.load(), 1);
    EXPECT_EQ(errors[i], "inner 11");
  }
}

TEST(ParallelTasks, OneThreadKeepsTasksStartedInsideATaskOnTheCallingThread) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  parallel_tasks(1, 3, [&](std::size_t) {
    parallel_tasks(1, 20, [&](std::size_t) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));  // time for another thread to steal
      if (std::this_thread::get_id() != caller) ++elsewhere;
    });
  });
  EXPECT_EQ(elsewhere.load(), 0);
}

TEST(ParallelTasks, HardwareThreadsIsAtLeastOne) { EXPECT_GE(hardware_threads(), 1); }

}  // namespace
}  // namespace locbench::experiments
