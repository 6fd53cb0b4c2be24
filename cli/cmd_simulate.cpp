// `locbench simulate SCENARIO -o LOG`: write the log a simulated robot would record.
#include <fmt/format.h>

#include <iostream>

#include "cli/commands.h"
#include "core/errors.h"
#include "core/output_file.h"
#include "core/trajectory.h"
#include "datasets/io/bag_log.h"
#include "datasets/io/carmen_writer.h"
#include "datasets/io/tum_writer.h"
#include "datasets/sim/presets.h"
#include "datasets/sim/scenario_json.h"
#include "datasets/sim/simulator.h"

namespace locbench::cli {
using io::write_carmen_log, io::write_tum;
namespace {

struct SimulateArgs {
  std::string scenario;
  std::uint64_t seed = 1;
  std::string out;
  std::string truth_tum;
  std::string ros1_bag;
  std::string ros2_bag;
  std::string mcap;
  bool print_scenario = false;
};

// A preset name, or a JSON scenario file (which may start from a preset with "preset": NAME).
sim::Scenario resolve_scenario(const std::string& spec) {
  if (std::filesystem::exists(spec)) return sim::load_scenario(spec);
  if (spec.ends_with(".json") || spec.find('/') != std::string::npos) {
    throw InputError(spec, 0, "no such scenario file (a preset name has no '/' or .json; see `locbench list`)");
  }
  sim::Scenario s = sim::preset(spec);
  sim::check_scenario_limits(s, spec);
  return s;
}

int simulate(const SimulateArgs& args) {
  const sim::Scenario scenario = resolve_scenario(args.scenario);
  if (args.print_scenario) {
    std::cout << sim::to_json(scenario).dump(2) << '\n';
    return kExitOk;
  }
  if (args.out.empty() && args.ros1_bag.empty() && args.ros2_bag.empty() && args.mcap.empty()) {
    throw UsageError(
        "simulate: give the log to write with -o FILE (or --ros1-bag FILE, --ros2-bag FOLDER, --mcap FILE)");
  }
  check_outputs(
      {args.scenario},
      {{"-o", args.out}, {"--truth-tum", args.truth_tum}, {"--ros1-bag", args.ros1_bag}, {"--mcap", args.mcap}});
  if (!args.ros2_bag.empty() && std::filesystem::exists(args.ros2_bag)) {
    throw InputError(args.ros2_bag, 0, "exists already (expected a new folder for the ROS 2 bag)");
  }
  const sim::SimulationResult result = sim::simulate(scenario, args.seed);
  if (!args.out.empty()) write_carmen_log(result.log, args.out);
  if (!args.ros1_bag.empty()) io::write_bag_log(result.log, args.ros1_bag, io::BagFormat::kRos1);
  if (!args.ros2_bag.empty()) io::write_bag_log(result.log, args.ros2_bag, io::BagFormat::kRos2);
  if (!args.mcap.empty()) io::write_bag_log(result.log, args.mcap, io::BagFormat::kMcap);
  if (!args.truth_tum.empty()) {
    const Trajectory truth = sim::true_trajectory(result);
    write_tum(truth, args.truth_tum);
  }
  const auto [t0, t1] = result.log.time_span();
  std::cerr << fmt::format(
      "wrote {}: scenario {}, seed {}, {:.1f} s, {} ENCODER, {} ODOM, {} COMPASS, {} FLASER, {} "
      "TRUEPOS, {} true slip events\n",
      !args.out.empty()        ? args.out
      : !args.ros1_bag.empty() ? args.ros1_bag
      : !args.ros2_bag.empty() ? args.ros2_bag
                               : args.mcap,
      scenario.name, args.seed, t1 - t0, result.log.encoders.size(), result.log.odometry.size(),
      result.log.compass.size(), result.log.laser.size(), result.log.truth.size(), result.slips.size());
  return kExitOk;
}

}  // namespace

Action add_simulate_command(CLI::App& app) {
  const auto [cmd, args] =
      add_verb<SimulateArgs>(app, "simulate", "Simulate a scenario and write its log (CARMEN format, .gz to compress)");
  cmd->add_option("scenario", args->scenario, "A scenario name (see `locbench list`) or a scenario JSON file")
      ->required();
  add_seed_option(cmd, args->seed, "Seed of every noise source")->capture_default_str();
  cmd->add_option("-o,--out", args->out, "Log file to write (.clf or .clf.gz)");
  cmd->add_option("--truth-tum", args->truth_tum, "Also write the true trajectory in TUM format");
  cmd->add_option(
      "--ros1-bag", args->ros1_bag,
      "Also write the log as a ROS 1 bag: /odom, /ground_truth, /scan, /imu (COMPASS), /tf_static (no ENCODER)");
  cmd->add_option("--ros2-bag", args->ros2_bag, "Also write the log as a ROS 2 sqlite3 bag folder (the same topics)");
  cmd->add_option("--mcap", args->mcap,
                  "Also write the log as a ROS 2 bag in one MCAP file, zstd chunks (the same topics)");
  cmd->add_flag("--print-scenario", args->print_scenario,
                "Print the scenario's full JSON (every option with its value) and exit");
  return [args = args] { return simulate(*args); };
}

}  // namespace locbench::cli
