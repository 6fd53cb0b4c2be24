#pragma once
// Test helpers for data on disk: real datasets (skip when absent) and scratch files.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "datasets/catalog/data_root.h"

namespace locbench::testing {

// Skips the current test with a clear message when a dataset file or folder is missing.
#define LOCBENCH_REQUIRE_DATA(relative_path)                                                        \
  do {                                                                                              \
    if (!std::filesystem::exists(::locbench::catalog::data_root() / (relative_path))) {             \
      GTEST_SKIP() << "dataset not found: " << (::locbench::catalog::data_root() / (relative_path)) \
                   << " (set LOCBENCH_DATA to the folder holding ../shared/datasets)";              \
    }                                                                                               \
  } while (0)

// The whole content of a file as written (binary); empty when it cannot be opened.
inline std::string file_contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh scratch directory for one test, removed at the end of the test.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("locbench_" + std::string(info->test_suite_name()) + "_" +
                                                      info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::filesystem::path file(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace locbench::testing
