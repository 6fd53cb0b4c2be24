#pragma once
// Deterministic shards of an experiment's tasks for batch systems (`locbench run --shard K/N`):
// shard K of N holds the tasks i with i mod N == K − 1, so every task is in exactly one shard,
// shards differ in size by at most one task, and an experiment of one task runs whole in shard 1.
#include <string>
#include <vector>

namespace locbench::experiments {

struct Shard {
  int index = 1;  // K, 1-based
  int count = 1;  // N
};

// "K/N" with 1 ≤ K ≤ N; UsageError otherwise (e.g. "0/3", "4/3", "2", "a/b").
Shard parse_shard(const std::string& text);
// The tasks of `shard` among tasks 0 … task_count − 1, ascending.
std::vector<int> shard_tasks(const Shard& shard, int task_count);

}  // namespace locbench::experiments
