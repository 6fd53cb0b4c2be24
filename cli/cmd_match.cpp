// `locbench match --map MAP.json --log LOG [--matcher NAME] [--report out.json] [--tum out.txt]`:
// match every laser scan of a user's log against their line map (chapter 5) from the pose the
// log gives for the scan (the FLASER pose, or the odometry interpolated at the scan's stamp
// when that is zero, as in *.from_bag logs), correct it with chapter 6's least squares, and
// report per-scan statistics; --tum writes the corrected poses (TUM format, for evo).
#include <fmt/format.h>

#include <cmath>

#include "algorithms/pose_correction/pose_correction.h"
#include "cli/bag_topic_options.h"
#include "cli/commands.h"
#include "cli/pose_report.h"
#include "core/checksum.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/output_file.h"
#include "core/statistics.h"
#include "datasets/io/log_loader.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/sim/worlds.h"
#include "pipelines/laser_matchers.h"

namespace locbench::cli {
using io::odometry_trajectory;
namespace {

struct MatchArgs {
  BagTopicArgs topics;  // --odom, --truth, --scan, --heading, --joints
  std::string map;
  std::string log;
  std::string matcher = "eap";
  std::string report;
  std::string tum;
};

bool is_zero(const Pose2& p) { return p.x == 0.0 && p.y == 0.0 && p.theta == 0.0; }

int match(const MatchArgs& a, const std::string& command_line) {
  check_outputs({a.map, a.log}, {{"--report", a.report}, {"--tum", a.tum}});
  const LineMap map = sim::load_world(a.map);
  if (map.segments.empty()) throw InputError(a.map, 0, "a map with at least one segment");
  const catalog::LoadedLog loaded = load_scan_log(a.log);
  const Log& log = loaded.log;
  if (a.matcher == "agglomerative") {
    double work = 0.0;
    for (const LaserReading& reading : log.laser) work += std::pow(static_cast<double>(reading.scan.ranges.size()), 2);
    limits::check(work, limits::kAgglomerativeWork, a.log, "the scans' beams^2 (agglomerative is quadratic in them)");
  }
  const auto matchers = experiments::make_matchers({a.matcher}, experiments::default_matcher_options(), &map);
  const laser::SegmentMatcher& matcher = *matchers.front();
  const std::optional<Trajectory> odom =
      log.odometry.empty() ? std::nullopt : std::optional<Trajectory>(odometry_trajectory(log));

  std::vector<double> segments, fixed, shift, turn, points;
  Trajectory corrected;  // for --tum
  std::size_t skipped = 0;
  for (const LaserReading& reading : log.laser) {
    Pose2 estimate = reading.pose;
    if (is_zero(estimate)) {
      const auto p = odom ? odom->pose_at(reading.scan.timestamp) : std::nullopt;
      if (!p) {
        ++skipped;
        continue;
      }
      estimate = *p;
    }
    const laser::MatchResult r = matcher.match(reading.scan, map, estimate);
    const auto c = pose_correction::correct_pose(r.matches, map, estimate, reading.scan.sensor_pose);
    std::size_t n = 0;
    for (const auto& m : r.matches) n += m.points.size();
    std::size_t valid = 0;
    for (std::size_t i = 0; i < reading.scan.ranges.size(); ++i) valid += reading.scan.valid(i);
    segments.push_back(static_cast<double>(r.matches.size()));
    fixed.push_back(c.position_fixed ? 1.0 : 0.0);
    shift.push_back(std::hypot(c.delta.x(), c.delta.y()));
    turn.push_back(std::abs(c.delta.z()));
    points.push_back(valid ? static_cast<double>(n) / static_cast<double>(valid) : 0.0);
    corrected.push_back({reading.scan.timestamp, c.corrected});
  }
  if (segments.empty()) {
    throw InputError(a.log, 0, "a pose for each scan: FLASER poses or ODOM records covering them");
  }
  reports::Report report;
  auto& out = report.body;
  out.experiment = "match/" + a.matcher;
  out.description = "Scan-to-map matching (" + a.matcher + ") and chapter-6 correction of each scan";
  out.configuration = {{"map", a.map},
                       {"log", a.log},
                       {"matcher", a.matcher},
                       {"matcher_options", experiments::default_matcher_options()}};
  out.datasets.push_back(loaded.dataset);
  out.datasets.push_back({map.name.empty() ? "map" : map.name, a.map, file_checksum(a.map), map.segments.size(), 0.0});
  const std::string ds = reports::key_part(std::filesystem::path(a.log).filename().string());
  const auto add = [&](const char* variant, const char* unit, const std::vector<double>& v, const char* better) {
    reports::MetricResult m = reports::make_metric(a.matcher, ds, variant, unit, "scans", v, false);
    m.better = better;
    out.results.push_back(std::move(m));
  };
  add("segments_matched", "", segments, "higher");
  add("position_fixed_fraction", "", fixed, "higher");
  add("points_matched_fraction", "", points, "higher");
  add("correction_translation", "m", shift, "stable");
  add("correction_rotation", "rad", turn, "stable");
  if (skipped) {
    out.notes.push_back(
        fmt::format("{} scans had no pose (no FLASER pose and no odometry at their "
                    "stamp) and were skipped.",
                    skipped));
  }
  return finish_pose_report(report, "match", command_line, a.report, corrected, a.tum);
}

}  // namespace

Action add_match_command(CLI::App& app, const std::string& command_line) {
  const auto [cmd, args] =
      add_verb<MatchArgs>(app, "match", "Match a log's laser scans against a line map and correct each pose (ch. 5–6)");
  cmd->add_option("--map", args->map, "Line map JSON: {\"name\", \"segments\": [[x1, y1, x2, y2], …]} [m]")->required();
  cmd->add_option("--log", args->log, "CARMEN log with FLASER scans (plain or .gz)")->required();
  cmd->add_option("--matcher", args->matcher, "eap (default), eap_indexed, split_and_merge, agglomerative or rwht");
  cmd->add_option("--report", args->report, "Write the report (JSON) here");
  cmd->add_option("--tum", args->tum, "Write the corrected poses here (TUM format)");
  return bag_topic_action(cmd, args, &MatchArgs::log,
                          [command_line](const MatchArgs& a) { return match(a, command_line); });
}

}  // namespace locbench::cli
