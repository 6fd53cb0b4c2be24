// locbench: benchmarks and evaluation for mobile-robot localization. One verb per job.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/input_limits.h"

int main(int argc, char** argv) {
  using namespace locbench::cli;
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);

  CLI::App app{"locbench — benchmarks and accuracy reports for mobile-robot localization"};
  app.set_version_flag("--version", std::string(LOCBENCH_VERSION));
  app.require_subcommand(1);
  app.footer(locbench::limits::limits_help());
  std::map<CLI::App*, Action> actions;
  auto add = [&](Action a) { actions[app.get_subcommands({}).back()] = std::move(a); };
  add(add_list_command(app));
  add(add_simulate_command(app));
  add(add_run_command(app, command_line));
  add(add_calibrate_command(app, command_line));
  add(add_gate_command(app));
  add(add_merge_command(app, command_line));
  add(add_report_command(app));
  add(add_match_command(app, command_line));
  add(add_localize_command(app, command_line));
  add(add_diagnose_command(app, command_line));

  // A first word that names no verb: CLI11 alone would say "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    std::string verbs;
    bool known = false;
    for (CLI::App* sub : app.get_subcommands({})) {
      verbs += (verbs.empty() ? "" : ", ") + sub->get_name();
      known = known || sub->check_name(argv[1]);
    }
    if (!known) {
      std::fprintf(stderr,
                   "locbench: usage error: unknown subcommand '%s': expected one of %s (see `locbench --help`)\n",
                   argv[1], verbs.c_str());
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help or the error
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    for (auto& [sub, action] : actions) {
      if (sub->parsed()) return action();
    }
    return kExitBadInput;
  } catch (const locbench::InputError& e) {
    std::fprintf(stderr, "locbench: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const locbench::UsageError& e) {
    std::fprintf(stderr, "locbench: usage error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "locbench: internal error: %s\n", e.what());
    return kExitInternal;
  }
}
