#pragma once
// Running the locbench binary (LOCBENCH_EXE) and other commands as a user would.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace locbench::testing {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs `command` through the shell (stderr joined to stdout).
inline Outcome run_shell(const std::string& command) {
  Outcome o;
  FILE* pipe = popen(("(" + command + ") 2>&1").c_str(), "r");
  if (!pipe) return o;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), pipe)) o.output += buf.data();
  const int status = pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

inline Outcome run_locbench(const std::string& args) { return run_shell(std::string(LOCBENCH_EXE) + " " + args); }

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace locbench::testing
