// The README's first screen serves a newcomer and stays true: within its first 60 lines it says
// what locbench is, gives the two commands, where the binary and the page are, and the commands
// most people want next — and every one of those commands runs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli/cli_helpers.h"

namespace locbench {
namespace {

constexpr std::size_t kFirstScreen = 60;
const std::string kBinary = "build/release/cli/locbench";

std::vector<std::string> first_screen() {
  std::ifstream in(std::string(LOCBENCH_SOURCE_DIR) + "/README.md");
  std::vector<std::string> lines;
  for (std::string line; lines.size() < kFirstScreen && std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The commands of the first screen's shell blocks that call the binary, without their comments.
std::vector<std::string> binary_commands(const std::vector<std::string>& lines) {
  std::vector<std::string> out;
  bool in_block = false;
  for (const std::string& line : lines) {
    if (line.starts_with("```")) {
      in_block = !in_block;
      continue;
    }
    if (!in_block || !line.starts_with(kBinary + " ")) continue;
    std::string command = line.substr(0, line.find(" #"));
    while (!command.empty() && command.back() == ' ') command.pop_back();
    out.push_back(command.substr(kBinary.size() + 1));
  }
  return out;
}

TEST(ReadmeFirstScreen, SaysWhatANewcomerNeedsWithinSixtyLines) {
  std::string text;
  for (const std::string& l : first_screen()) text += l + "\n";
  for (const char* needed :
       {"## Two commands", "make run", "make test", "build/release/cli/locbench", "out/report.html", "diagnose my.clf",
        "--log my.clf", "locbench simulate corridor --seed 7 -o my.clf"}) {
    EXPECT_NE(text.find(needed), std::string::npos) << needed;
  }
}

TEST(ReadmeFirstScreen, EveryCommandItShowsRuns) {
  const std::vector<std::string> commands = binary_commands(first_screen());
  ASSERT_EQ(commands.size(), 4u) << "the default suite, the page, diagnose and a real-data experiment";
  const auto dir = std::filesystem::temp_directory_path() / ("locbench_readme_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string cd = "cd '" + dir.string() + "' && ";
  // The log the first screen tells a user without one to write.
  const auto made = testing::run_shell(cd + LOCBENCH_EXE + " simulate corridor --seed 7 -o my.clf");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  for (std::string command : commands) {
    // The default suite is what `make run` runs and `make test`'s gate checks; here one quick
    // experiment stands in for it, writing the same folder the next command reads.
    if (command == "run --out out") command = "run odometry/sim_corridor --runs 2 --out out";
    const auto r = testing::run_shell(cd + LOCBENCH_EXE + " " + command);
    EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.output;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "report.html"));
  EXPECT_TRUE(std::filesystem::exists(dir / "mine" / "diagnosis" / "real_logs.json"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace locbench
