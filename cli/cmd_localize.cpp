// `locbench localize --method NAME --log LOG (--map MAP.json | --map-from-log SECONDS)
//  [--start X,Y,THETA] [--options FILE] [--seed N] [--report out.json] [--tum out.txt]`:
// localize every laser scan of a log in a line map with one of the global-localization
// baselines (mcl, grid_markov — start unknown) or a Kalman tracker (ekf_eap,
// kalman_line_features — start given, or the log's first true pose). With --map-from-log the
// map is built from the log's own scans in its first SECONDS (split-and-merge lines placed by the
// odometry; the reference is then the odometry) — the way to try it on logs that come without a
// map, e.g. the Freiburg ones. Scored against TRUEPOS when the log has it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "baselines/global/grid_markov.h"
#include "baselines/global/monte_carlo_localization.h"
#include "baselines/global/odometry_motion_model.h"
#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "cli/pose_report.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/json_file.h"
#include "core/output_file.h"
#include "datasets/io/log_loader.h"
#include "datasets/sim/worlds.h"
#include "experiment_framework/experiment.h"
#include "pipelines/global_harness.h"

namespace locbench::cli {
namespace {

namespace g = experiments::global;

struct LocalizeArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::string method = "mcl";
  std::string map;
  double map_from_log = 0.0;
  std::string log;
  std::string start;
  std::string options;
  std::uint64_t seed = 1;
  std::string report;
  std::string tum;
};

std::string canonical_method(const std::string& m) {
  if (m == "markov-grid" || m == "grid" || m == "markov_grid") return "grid_markov";
  if (m == "ekf") return "ekf_eap";
  if (m == "line-kalman" || m == "line_kalman") return "kalman_line_features";
  return m;
}

Pose2 parse_start(const std::string& text) {
  std::istringstream in(text);
  double v[3];
  char comma = 0;
  if (!(in >> v[0] >> comma >> v[1] >> comma >> v[2]) || !in.eof() || !std::isfinite(v[0]) || !std::isfinite(v[1]) ||
      !std::isfinite(v[2])) {
    throw UsageError("--start: expected X,Y,THETA in metres and radians, got '" + text + "'");
  }
  return {v[0], v[1], v[2]};
}

// Runs `f`; a bad-option error it throws is re-thrown naming `file` (when given).
template <typename F>
auto naming_file(const std::string& file, F f) {
  if (file.empty()) return f();
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(file, 0, e.what());
  } catch (const UsageError& e) {
    throw InputError(file, 0, e.what());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, 0, std::string("wrong type of an option: ") + e.what());
  }
}

// Which scans a global localizer updates on: the first, then every scan after the odometry
// moved update_min_distance or turned update_min_angle (as MCL and grid Markov gate).
std::vector<bool> update_flags(const std::vector<g::ScanStep>& steps, double min_distance, double min_angle) {
  std::vector<bool> flags(steps.size(), false);
  std::optional<Pose2> last;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (last) {
      const auto d = baselines::global::odometry_delta(*last, steps[i].odometry);
      if (baselines::global::moved_less_than(d, *last, steps[i].odometry, min_distance, min_angle)) continue;
    }
    last = steps[i].odometry;
    flags[i] = true;
  }
  return flags;
}

// The run's work against its limit (limits::kMclWork, kGridMarkovWork). Grid Markov's is known
// before any update (cells × (beams + 10) × updates). MCL's depends on how many particles KLD
// sampling keeps, so the work every run must do (initial_particles, then min_particles with KLD or
// max_particles without) is checked before any update, and the work done is counted as the filter
// runs: the run stops with exit 2 before an update would pass the limit.
struct WorkBudget {
  std::string method, file;
  std::vector<bool> updates;
  double per_hypothesis = 0.0;  // field.beams + 80 (MCL)
  double done = 0.0;
};

WorkBudget check_work(const std::string& method, const nlohmann::json& options, const std::vector<g::ScanStep>& steps,
                      const g::Localizer& loc, const std::string& file) {
  WorkBudget b{method, file, {}, 0.0, 0.0};
  if (method == "mcl") {
    baselines::global::MclOptions o;
    baselines::global::from_json(options.at("mcl"), o);
    b.updates = update_flags(steps, o.update_min_distance, o.update_min_angle);
    b.per_hypothesis = o.field.beams + 80.0;
    const double updates = static_cast<double>(std::count(b.updates.begin(), b.updates.end(), true));
    const double least =
        (o.initial_particles + std::max(0.0, updates - 1.0) * (o.kld ? o.min_particles : o.max_particles)) *
        b.per_hypothesis;
    limits::check(least, limits::kMclWork, file,
                  fmt::format("mcl: at least {} particles x ({} beams + 80) over {} updates ({})", o.initial_particles,
                              o.field.beams, updates,
                              o.kld ? "min_particles after the first" : "max_particles after the first, no KLD"));
  } else if (method == "grid_markov") {
    baselines::global::GridMarkovOptions o;
    baselines::global::from_json(options.at("grid_markov"), o);
    const auto flags = update_flags(steps, o.update_min_distance, o.update_min_angle);
    const double updates = static_cast<double>(std::count(flags.begin(), flags.end(), true));
    const double cells = static_cast<double>(loc.hypotheses());
    limits::check(cells * (o.field.beams + 10.0) * updates, limits::kGridMarkovWork, file,
                  fmt::format("grid_markov: {} cells x ({} beams + 10) x {} updates", cells, o.field.beams, updates));
  }
  return b;
}

// Runs the localizer over every scan, counting MCL's work (the particles weighed with
// field.beams, and 80 beams' worth each for KLD resampling) against the limit.
std::vector<Pose2> run_within_budget(g::Localizer& loc, const std::vector<g::ScanStep>& steps, WorkBudget& b) {
  std::vector<Pose2> out;
  out.reserve(steps.size());
  const double limit = limits::kMclWork.max;
  const std::size_t total = static_cast<std::size_t>(std::count(b.updates.begin(), b.updates.end(), true));
  std::size_t made = 0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const bool counted = b.method == "mcl" && b.updates[i];
    const double before = counted ? static_cast<double>(loc.hypotheses()) : 0.0;
    if (counted && b.done + before * b.per_hypothesis > limit) {
      throw InputError(b.file, 0,
                       fmt::format("mcl: {:.6g} particle-beams done after {} of {} updates, and the next would pass "
                                   "the limit {} (particles x (field.beams + 80) summed over the updates; see "
                                   "`locbench --help`, \"Input limits\"): use fewer max_particles, a larger kld_bin "
                                   "or a larger update_min_distance",
                                   b.done, made, total, limits::limit_text(limit)));
    }
    loc.step(steps[i]);
    out.push_back(loc.pose());
    if (counted) {
      b.done += before * (b.per_hypothesis - 80.0) + static_cast<double>(loc.hypotheses()) * 80.0;
      ++made;
    }
  }
  return out;
}

int localize(const LocalizeArgs& a, const std::string& command_line) {
  const std::string method = canonical_method(a.method);
  if (!std::isfinite(a.map_from_log) || a.map_from_log < 0.0 || a.map_from_log > 1e6) {
    throw UsageError(fmt::format("--map-from-log {}: expected a duration in (0, 1e6] s", a.map_from_log));
  }
  if (a.map.empty() == (a.map_from_log <= 0.0)) {
    throw UsageError("give exactly one of --map FILE and --map-from-log SECONDS");
  }
  check_outputs({a.log, a.map, a.options}, {{"--report", a.report}, {"--tum", a.tum}});
  nlohmann::json options = g::default_method_options();
  if (!a.options.empty()) {
    const nlohmann::json user = read_json_file(a.options, "--options file (JSON)");
    options = naming_file(a.options, [&] { return experiments::merge_config(options, user); });
  }
  const catalog::LoadedLog loaded = load_scan_log(a.log);
  const Log& log = loaded.log;
  std::vector<g::ScanStep> steps = g::scan_steps(log);
  if (steps.empty()) {
    throw InputError(a.log, 0, "odometry (ODOM records or FLASER odometry) covering the scans");
  }
  LineMap map;
  std::string reference = log.truth.empty() ? "" : "truth";
  if (!a.map.empty()) {
    map = sim::load_world(a.map);
    if (map.segments.empty()) throw InputError(a.map, 0, "a map with at least one segment");
  } else {
    const double t0 = steps.front().t, t1 = t0 + a.map_from_log;
    map = g::map_from_scans(steps, t0, t1, 5);
    if (map.segments.empty()) throw InputError(a.log, 0, "lines in the scans of the first window");
    for (auto& s : steps) s.reference = s.odometry;
    reference = "odometry (map built from the log)";
  }
  std::optional<Pose2> start;
  if (!a.start.empty())
    start = parse_start(a.start);
  else if (steps.front().reference)
    start = steps.front().reference;
  if (!g::is_global_method(method) && !start) {
    throw UsageError(method + " tracks from a known start: give --start X,Y,THETA (the log has no TRUEPOS)");
  }
  // The options are read here: their errors name the --options file.
  auto loc = naming_file(a.options, [&] { return g::make_localizer(method, map, options, start, a.seed); });
  WorkBudget budget = check_work(method, options, steps, *loc, a.options.empty() ? a.log : a.options);
  const std::vector<Pose2> est = run_within_budget(*loc, steps, budget);

  Trajectory traj;
  for (std::size_t i = 0; i < steps.size(); ++i) traj.push_back({steps[i].t, est[i]});
  reports::Report report;
  auto& out = report.body;
  out.experiment = "localize/" + method;
  out.description = "Localization of every scan of a log in a line map (" + method + ")";
  out.configuration = {{"map", a.map.empty() ? "from the log" : a.map},
                       {"log", a.log},
                       {"method", method},
                       {"seed", a.seed},
                       {"method_options", options}};
  out.seeds.push_back(a.seed);
  out.datasets.push_back(loaded.dataset);
  if (!a.map.empty()) {
    out.datasets.push_back(
        {map.name.empty() ? "map" : map.name, a.map, file_checksum(a.map), map.segments.size(), 0.0});
  }
  const std::string ds = reports::key_part(std::filesystem::path(a.log).filename().string());
  out.results.push_back(reports::make_metric(method, ds, "memory", "bytes", "estimate",
                                             std::vector<double>{static_cast<double>(loc->memory_bytes())}, false));
  if (!reference.empty()) {
    std::vector<double> pos, head;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      pos.push_back(translation_distance(est[i], *steps[i].reference));
      head.push_back(std::abs(angle_diff(est[i].theta, steps[i].reference->theta)));
    }
    out.results.push_back(reports::make_metric(method, ds, "position_error", "m", "scans", pos, false));
    out.results.push_back(reports::make_metric(method, ds, "heading_error", "rad", "scans", head, false));
    const auto c = g::converged_from(est, steps, 0, steps.size(), {});
    out.notes.push_back(
        c ? fmt::format("Within 0.5 m and 0.35 rad of the {} from {:.1f} s ({:.1f} m travelled) to the end; "
                        "final error {:.3f} m.",
                        reference, steps[*c].t - steps[0].t, g::path_length(steps, 0, *c), pos.back())
          : fmt::format("Never settled within 0.5 m and 0.35 rad of the {}; final error {:.3f} m.", reference,
                        pos.back()));
  }
  return finish_pose_report(report, "localize", command_line, a.report, traj, a.tum);
}

}  // namespace

Action add_localize_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] = add_verb<LocalizeArgs>(
      app, "localize", "Localize a log's scans in a line map: MCL, grid Markov or a Kalman tracker");
  cmd->add_option("--method", args->method,
                  "mcl (default), grid_markov (markov-grid), ekf_eap (ekf) or kalman_line_features");
  cmd->add_option("--map", args->map, "Line map JSON: {\"name\", \"segments\": [[x1, y1, x2, y2], …]} [m]");
  cmd->add_option("--map-from-log", args->map_from_log,
                  "Build the map from the log's own scans in its first SECONDS (reference = odometry)");
  cmd->add_option("--log", args->log, "CARMEN log with FLASER scans and odometry (plain or .gz)")->required();
  cmd->add_option("--start", args->start, "Start pose X,Y,THETA for the Kalman trackers [m, rad]");
  cmd->add_option("--options", args->options,
                  "JSON overriding the methods' options (keys: mcl, grid_markov, ekf_eap, kalman_line_features)");
  add_seed_option(cmd, args->seed, "Seed of MCL's random numbers (default 1)");
  cmd->add_option("--report", args->report, "Write the report (JSON) here");
  cmd->add_option("--tum", args->tum, "Write the estimated poses here (TUM format)");
  return bag_topic_action(cmd, args, &LocalizeArgs::log,
                          [command_line](const LocalizeArgs& a) { return localize(a, command_line); });
}

}  // namespace locbench::cli
