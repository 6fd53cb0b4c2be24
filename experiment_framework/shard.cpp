#include "experiment_framework/shard.h"

#include <charconv>

#include "core/errors.h"

namespace locbench::experiments {
namespace {

bool parse_int(const std::string& s, int& out) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  if (slash == std::string::npos || !parse_int(text.substr(0, slash), s.index) ||
      !parse_int(text.substr(slash + 1), s.count)) {
    throw UsageError("--shard " + text + ": expected K/N, e.g. 2/8 (shard 2 of 8)");
  }
  if (s.count < 1 || s.index < 1 || s.index > s.count) {
    throw UsageError("--shard " + text + ": need 1 ≤ K ≤ N");
  }
  return s;
}

std::vector<int> shard_tasks(const Shard& shard, int task_count) {
  std::vector<int> tasks;
  for (int i = shard.index - 1; i < task_count; i += shard.count) tasks.push_back(i);
  return tasks;
}

}  // namespace locbench::experiments
