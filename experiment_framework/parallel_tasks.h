#pragma once
// Runs independent tasks 0 … n−1 on up to `threads` worker threads (oneTBB: a task arena of that
// size with parallel_for over single indices, so uneven tasks balance). Each task must write only
// its own output slot; then the results do not depend on the thread count or on scheduling.
#include <cstddef>
#include <functional>
#include <thread>

namespace locbench::experiments {

// All cores of this machine (at least 1).
int hardware_threads();

// Calls fn(i) for every i in [0, n), at most `threads` at a time (≤ 1: in order on this thread).
// If tasks throw, every task still runs and the exception of the lowest index is rethrown, so
// the error seen does not depend on scheduling either. Called inside a task of another
// parallel_tasks, the tasks join that one's arena (its thread count; a thread that ran out of
// tasks there takes these), whatever `threads` says.
void parallel_tasks(int threads, std::size_t n, const std::function<void(std::size_t)>& fn);

}  // namespace locbench::experiments
