#pragma once
// One small file per verb; each registers its sub-command and returns the exit code.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace locbench::cli {

// Exit codes of every verb.
inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;  // a gate or check failed
inline constexpr int kExitBadInput = 2;     // bad input or usage
inline constexpr int kExitInternal = 3;     // a bug: please report

// A sub-command being declared: its CLI11 command and the arguments its options fill (shared
// with the action that runs once the command line is parsed).
template <class Args>
struct Verb {
  CLI::App* cmd;
  std::shared_ptr<Args> args;
};

// Adds the sub-command `name` to `app`, with fresh default arguments.
template <class Args>
Verb<Args> add_verb(CLI::App& app, const char* name, const char* description) {
  return {app.add_subcommand(name, description), std::make_shared<Args>()};
}

// --data, the dataset folder, as every verb that reads the catalog declares it.
inline void add_data_option(CLI::App* cmd, std::string& data) {
  cmd->add_option("--data", data, "Dataset folder (default: $LOCBENCH_DATA or ../shared/datasets)");
}

// --seed, as every verb that draws random numbers declares it: 0 … 2^53 − 1, the integers a
// JSON report keeps exactly (a negative seed is refused, not wrapped to 2^64 − 5).
// Text that is not an integer at all ("abc", "1.5") is named as such before the range check.
inline CLI::Option* add_seed_option(CLI::App* cmd, std::uint64_t& seed, const std::string& description) {
  const CLI::Validator integer(
      [](std::string& text) {
        const std::size_t digits = !text.empty() && text.front() == '-' ? 1 : 0;
        const bool ok =
            text.size() > digits && std::all_of(text.begin() + static_cast<std::ptrdiff_t>(digits), text.end(),
                                                [](unsigned char c) { return std::isdigit(c) != 0; });
        return ok ? std::string() : "Value " + text + " is not a whole number";
      },
      "INTEGER", "integer");
  return cmd->add_option("--seed", seed, description + " (0 … 2^53 − 1)")
      ->check(integer)
      ->check(CLI::Range(std::uint64_t{0}, (std::uint64_t{1} << 53) - 1));
}

// --threads, 1 … kMaxThreads (a range, not CLI11's "positive number", whose message prints
// the largest double in full).
inline constexpr int kMaxThreads = 1024;
inline CLI::Option* add_threads_option(CLI::App* cmd, int& threads, const std::string& description) {
  return cmd->add_option("--threads", threads, description + " (1 … 1024)")->check(CLI::Range(1, kMaxThreads));
}

// Each add_* registers a sub-command on `app` and returns the action to run when it is chosen.
using Action = std::function<int()>;
Action add_list_command(CLI::App& app);
Action add_simulate_command(CLI::App& app);
Action add_run_command(CLI::App& app, const std::string& command_line);
Action add_gate_command(CLI::App& app);
Action add_calibrate_command(CLI::App& app, const std::string& command_line);
Action add_merge_command(CLI::App& app, const std::string& command_line);
Action add_report_command(CLI::App& app);
Action add_match_command(CLI::App& app, const std::string& command_line);
Action add_localize_command(CLI::App& app, const std::string& command_line);
Action add_diagnose_command(CLI::App& app, const std::string& command_line);

}  // namespace locbench::cli
