#include "experiment_framework/parallel_tasks.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <exception>
#include <vector>

namespace locbench::experiments {

int hardware_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

namespace {
// How many of parallel_tasks' arena tasks this thread is running (0: none).
thread_local int nesting = 0;
}  // namespace

void parallel_tasks(int threads, std::size_t n, const std::function<void(std::size_t)>& fn) {
  std::vector<std::exception_ptr> errors(n);
  const auto one = [&](std::size_t i) {
    try {
      fn(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  const auto each = [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          ++nesting;
          for (std::size_t i = r.begin(); i != r.end(); ++i) one(i);
          --nesting;
        },
        tbb::simple_partitioner());
  };
  if (nesting > 0 && n > 1) {
    each();  // inside a task: in the enclosing arena, whose idle threads take these tasks too
  } else if (threads <= 1 || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) one(i);
  } else {
    tbb::task_arena arena(threads);
    arena.execute(each);
  }
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace locbench::experiments
