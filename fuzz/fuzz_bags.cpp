// ROS bag readers (ROS 1, ROS 2 sqlite3, MCAP): the input's first byte picks the format (its value
// mod 3: .bag, .db3, .mcap), the rest is the file, read as a log with the default topics.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "datasets/io/log_loader.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("locbench_fuzz_bags_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  constexpr const char* kExtensions[] = {".bag", ".db3", ".mcap"};
  const std::filesystem::path file = dir / (std::string("input") + kExtensions[data[0] % 3]);
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  return locbench::fuzz::accept_or_reject([&] { locbench::io::load_log(file.string()); });
}
