#pragma once
// A progress bar on stderr: drawn only when stderr is a terminal and the task has run for more
// than a second; silent otherwise (CI logs, pipes).
#include <chrono>
#include <string>

namespace locbench::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();  // clears the bar
  void update(double fraction);

 private:
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  bool drawn_ = false;
  int last_permille_ = -1;
};

}  // namespace locbench::cli
