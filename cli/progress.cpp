#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace locbench::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), start_(std::chrono::steady_clock::now()), enabled_(isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void ProgressBar::update(double fraction) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < 1.0) return;
  const int permille = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 1000.0);
  if (permille == last_permille_) return;
  last_permille_ = permille;
  constexpr int kWidth = 30;
  const int filled = permille * kWidth / 1000;
  std::fprintf(stderr, "\r%-32.32s [%.*s%*s] %5.1f%%  %.0fs", label_.c_str(), filled, "##############################",
               kWidth - filled, "", permille / 10.0, elapsed);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace locbench::cli
