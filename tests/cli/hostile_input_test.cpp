// The hostile-input suite of record: one table of inputs a hostile or careless user
// gives locbench — input files, arguments, the exit code expected and a substring of the message.
// Every case runs the real binary under `timeout 60`: no crash, no hang, no "internal error"
// (exit 3), and every bad input names what was wrong. Add a row for every new hostile case. The
// timeout catches a hang, it times nothing: a limit's input takes ≤ 10 s in the Release build, which
// scripts/time_limits.sh measures; in this sanitizer build, beside other tests, it may take longer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "tests/cli/cli_helpers.h"
#include "tests/test_data.h"

namespace locbench {
namespace {

struct HostileCase {
  HostileCase(std::string n, std::string s, std::string a, int e, std::string m, std::string p = "")
      : name(std::move(n)),
        setup(std::move(s)),
        args(std::move(a)),
        exit_code(e),
        message(std::move(m)),
        prefix(std::move(p)) {}
  std::string name;
  // Shell commands run in the scratch folder before the case ({exe}, {src}, {d} substituted).
  std::string setup;
  std::string args;  // locbench's arguments ({d}: the scratch folder, {src}: the source tree)
  int exit_code;
  std::string message;  // a substring of stdout + stderr
  std::string prefix;   // shell words before the command (an environment, a lock holder)
};

// A residual histogram with `bins` 1° bins centred on 0 and `filled` of them holding counts of
// a normal shape (the rest zero).
std::string histogram(int bins, int filled, const std::string& count_override = "") {
  std::string edges, counts;
  for (int i = 0; i <= bins; ++i) edges += (i ? "," : "") + std::to_string(i - bins / 2);
  for (int i = 0; i < bins; ++i) {
    const int k = i - bins / 2;
    const int c = std::abs(k) * 2 < filled ? static_cast<int>(400.0 * std::exp(-0.5 * k * k / 9.0)) + 1 : 0;
    counts += (i ? "," : "") + (i == bins / 2 && !count_override.empty() ? count_override : std::to_string(c));
  }
  return R"({"residual": "r", "unit": "deg", "edges": [)" + edges + R"(], "counts": [)" + counts + "]}";
}

// Writes `text` to {d}/name in the setup (printf-safe: via a here-document).
std::string file(const std::string& name, const std::string& text) {
  return "cat > '{d}/" + name + "' <<'LOCBENCH_EOF'\n" + text + "\nLOCBENCH_EOF\n";
}

// A short simulated log with ENCODER, TRUEPOS, COMPASS and FLASER records (1 m straight; too
// short for `diagnose`, which wants 40 windows, enough for everything checked before that).
const std::string kShortLog =
    file("short.json",
         R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1.0}, "laser": {"enabled": true}})") +
    "{exe} simulate '{d}/short.json' --seed 3 -o '{d}/l.clf' >/dev/null 2>&1\n";
// The same run as a ROS 1 bag (l.bag), a ROS 2 bag (folder l2) and an MCAP file (l.mcap) with /odom,
// /ground_truth, /scan.
const std::string kShortBags =
    file("b.json", R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1.0},
                      "odometry": {"enabled": true}, "laser": {"enabled": true}})") +
    "{exe} simulate '{d}/b.json' --seed 3 --ros1-bag '{d}/l.bag' --ros2-bag '{d}/l2' --mcap '{d}/l.mcap' >/dev/null "
    "2>&1\n";
// A valid report (classic UMBmark on the example data).
const std::string kReport =
    "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1\n";
// The report claimed by `run --seed S` of experiment E: seeds and a run command line.
std::string run_report(const std::string& to, const std::string& seed, const std::string& experiment,
                       const std::string& revision = "") {
  return kReport + "sed -e 's/\"seeds\": \\[\\]/\"seeds\": [" + seed +
         "]/' -e 's|\"command_line\": \"[^\"]*\"|\"command_line\": \"locbench run --seed " + seed +
         "\"|' -e 's|calibrate/umbmark_classic|" + experiment + "|' " +
         (revision.empty() ? "" : "-e 's|\"git_revision\": \"[^\"]*\"|\"git_revision\": \"" + revision + "\"|' ") +
         "'{d}/r.json' > '" + to + "'\n";
}

// A histogram of 1,000 bins with the first 500 filled (a wide normal shape): the filled-bins limit.
const std::string kHist500 =
    "awk 'BEGIN{printf \"{\\\"residual\\\": \\\"r\\\", \\\"unit\\\": \\\"deg\\\", \\\"edges\\\": [0\"; "
    "for(i=1;i<=1000;i++) printf \",%d\", i; printf \"], \\\"counts\\\": [\"; "
    "for(i=0;i<1000;i++) printf \"%s%d\", (i ? \",\" : \"\"), (i < 500 ? 1 + int(400 * exp(-0.5 * ((i - 250) / 80) ^ "
    "2)) "
    ": 0); print \"]}\"}' > '{d}/h.json'\n";
// A CARMEN log of `n` ENCODER records and nothing else (no reference): `diagnose` counts them first.
std::string encoder_log(int n) {
  return "awk 'BEGIN{for(i=0;i<" + std::to_string(n) +
         ";i++) printf \"ENCODER %d %d %.3f locbench %.3f\\n\", i, i, i * 0.01, i * 0.01}' > '{d}/e.clf'\n";
}
// A CARMEN log of `scans` FLASER scans of `beams` ranges each, at a pose in the room map.
std::string scan_log(int scans, int beams) {
  return "awk 'BEGIN{for(s=0;s<" + std::to_string(scans) + ";s++){printf \"FLASER " + std::to_string(beams) +
         "\"; for(i=0;i<" + std::to_string(beams) +
         ";i++) printf \" %.2f\", 1.5 + (i % 7) * 0.1; "
         "printf \" 2 2 0.3 2 2 0.3 %.1f locbench %.1f\\n\", s * 0.2, s * 0.2}}' > '{d}/s.clf'\n";
}

// Google Benchmark results of A and B: b.json, the baseline (A 50 ns, B 100 ns), c.json, the
// current run (A `current_a`, B `current_b` ns), and rules.json, a rule on the speed ratio A/B.
std::string speed_ratio_gate(const std::string& current_a, const std::string& current_b) {
  const auto benchmarks = [](const std::string& a, const std::string& b) {
    return R"({"benchmarks": [{"name": "A", "real_time": )" + a +
           R"(, "time_unit": "ns"}, {"name": "B", "real_time": )" + b + R"(, "time_unit": "ns"}]})";
  };
  return file("b.json", benchmarks("50", "100")) + file("c.json", benchmarks(current_a, current_b)) +
         file("rules.json",
              R"({"speed_ratios": [{"name": "a_vs_b", "numerator": "bench:A", "denominator": "bench:B"}]})");
}

const std::vector<HostileCase>& cases() {
  static const std::vector<HostileCase> all = {
      // 1. The histogram crash, the superlinear fits, counts validation.
      {"histogram_10000_bins_does_not_crash", file("h.json", histogram(10000, 10)), "diagnose {d}/h.json", 0,
       "verdict:"},
      {"histogram_200_filled_bins_in_seconds", file("h.json", histogram(200, 200)), "diagnose {d}/h.json", 0,
       "verdict:"},
      {"histogram_count_1e18", file("h.json", histogram(20, 10, "1e18")), "diagnose {d}/h.json", 2,
       "exceeds the limit"},
      {"histogram_all_in_one_bin",
       file("h.json", R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[0,0,900,0,0]})"),
       "diagnose {d}/h.json", 2, "at least 3 bins"},
      {"histogram_fractional_count", file("h.json", histogram(20, 10, "3.5")), "diagnose {d}/h.json", 2,
       "whole number"},
      {"histogram_1e400", file("h.json", histogram(20, 10, "1e400")), "diagnose {d}/h.json", 2, "number overflow"},
      {"histogram_is_a_folder", "mkdir '{d}/h.json'", "diagnose {d}/h.json", 2, "is a folder"},
      {"histogram_too_many_bins",
       "awk 'BEGIN{printf \"{\\\"residual\\\": \\\"r\\\", \\\"unit\\\": \\\"deg\\\", \\\"edges\\\": [0\"; "
       "for(i=1;i<=10001;i++) printf \",%d\", i; "
       "printf \"], \\\"counts\\\": [9\"; for(i=1;i<10001;i++) printf \",0\"; print \"]}\"}' > '{d}/h.json'",
       "diagnose {d}/h.json", 2, "counts: 10001 exceeds the limit 10000"},
      // 2. Limits checked before work.
      {"simulate_1e9_beams", file("s.json", R"({"preset": "corridor", "laser": {"beams": 1000000000}})"),
       "simulate {d}/s.json -o {d}/o.clf", 2, "laser.beams"},
      {"simulate_waypoint_1e308",
       file("s.json", R"({"preset": "corridor", "motion": {"kind": "waypoints", "waypoints": [[1e308, 1e308]]}})"),
       "simulate {d}/s.json -o {d}/o.clf", 2, "motion.waypoints[0]"},
      {"simulate_1e8_runs",
       file("s.json", R"({"preset": "corridor", "motion": {"kind": "umbmark", "runs": 100000000}})"),
       "simulate {d}/s.json -o {d}/o.clf", 2, "motion.runs"},
      {"simulate_crawling_speed", file("s.json", R"({"preset": "corridor", "drive": {"speed": 1e-9}})"),
       "simulate {d}/s.json -o {d}/o.clf", 2, "duration"},
      {"run_set_runs_1e8", "", "run odometry/sim_corridor --set runs=100000000 --out {d}/out", 2,
       "exceeds the limit 1000"},
      {"run_runs_0", "", "run odometry/sim_corridor --runs 0 --out {d}/out", 2, "not in range 1 to 1000"},
      {"match_20000_beam_scan",
       kShortLog + "awk 'BEGIN{printf \"FLASER 20000\"; for(i=0;i<20000;i++) printf \" 1.0\"; print \" 0 0 0 0 0 0 1.0 "
                   "h 1.0\"}' > '{d}/big.clf'",
       "match --map {src}/examples/room_map.json --log {d}/big.clf --matcher agglomerative", 2,
       "exceeds the limit 10000"},
      // 3. Outputs never overwrite inputs.
      {"calibrate_report_onto_input", "cp '{src}/examples/umbmark_trilobot.json' '{d}/m.json'",
       "calibrate umbmark-classic {d}/m.json --report {d}/m.json", 2, "would overwrite the input"},
      {"report_onto_input", kReport, "report {d}/r.json -o {d}/r.json", 2, "would overwrite the input"},
      {"merge_onto_an_input_shard", "mkdir -p '{d}/s1' '{d}/s2' '{d}/s3' && echo '{}' > '{d}/s1/x.shard-1-of-3.json'",
       "merge {d}/s1 {d}/s2 {d}/s3 -o {d}/s1/x.shard-1-of-3.json", 2, "lies in the input folder"},
      {"diagnose_report_onto_log", kShortLog, "diagnose {d}/l.clf --report {d}/l.clf", 2, "would overwrite the input"},
      {"diagnose_report_onto_log_through_symlink", kShortLog + "ln -s l.clf '{d}/link.clf'",
       "diagnose {d}/l.clf --report {d}/link.clf", 2, "would overwrite the input"},
      {"match_tum_onto_log", kShortLog, "match --map {src}/examples/room_map.json --log {d}/l.clf --tum {d}/l.clf", 2,
       "would overwrite the input"},
      {"localize_tum_onto_log", kShortLog,
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --tum {d}/l.clf", 2, "would overwrite the input"},
      {"simulate_onto_scenario", file("s.json", R"({"preset": "corridor"})"), "simulate {d}/s.json -o {d}/s.json", 2,
       "would overwrite the input"},
      {"simulate_log_and_truth_same_file", "", "simulate corridor -o {d}/a.clf --truth-tum {d}/a.clf", 2,
       "name the same file"},
      {"gate_json_into_input_folder", "mkdir -p '{d}/X' && " + kReport + "cp '{d}/r.json' '{d}/X/a.json'",
       "gate {d}/X --baseline {d}/X --json {d}/X/a.json", 2, "lies in the input folder"},
      // 4. Write failures are errors.
      {"gate_json_disk_full", kReport, "gate {d}/r.json --baseline {d}/r.json --json /dev/full", 2, "No space left"},
      {"gate_markdown_disk_full", kReport, "gate {d}/r.json --baseline {d}/r.json --markdown /dev/full", 2,
       "No space left"},
      {"diagnose_report_disk_full", "", "diagnose {src}/examples/table_3_1_histogram.json --report /dev/full", 2,
       "No space left"},
      {"simulate_disk_full", "", "simulate corridor -o /dev/full", 2, "/dev/full"},
      // 6. A folder in use is refused; mixed runs do not pass a gate.
      {"run_into_a_locked_folder", "mkdir -p '{d}/out' && touch '{d}/out/.locbench.lock'",
       "run odometry/sim_corridor --runs 1 --out {d}/out", 2, "in use", "flock '{d}/out/.locbench.lock'"},
      {"gate_mixed_seeds",
       "mkdir -p '{d}/cur' && " + run_report("{d}/cur/a.json", "1", "calibrate/a") +
           run_report("{d}/cur/b.json", "2", "calibrate/b"),
       "gate {d}/cur --baseline {d}/cur", 2, "mix runs"},
      {"gate_mixed_revisions",
       "mkdir -p '{d}/cur' && " + run_report("{d}/cur/a.json", "1", "calibrate/a", "aaaa") +
           run_report("{d}/cur/b.json", "1", "calibrate/b", "bbbb"),
       "gate {d}/cur --baseline {d}/cur", 2, "git revision"},
      {"gate_mixed_seeds_allowed",
       "mkdir -p '{d}/cur' && " + run_report("{d}/cur/a.json", "1", "calibrate/a") +
           run_report("{d}/cur/b.json", "2", "calibrate/b"),
       "gate {d}/cur --baseline {d}/cur --allow-mixed", 0, "gate: PASSED"},
      // 7. No "internal error": file, key or line, and what was expected.
      {"scenario_1e400", file("s.json", R"({"preset": "corridor", "drive": {"speed": 1e400}})"),
       "simulate {d}/s.json -o {d}/o.clf", 2, "number overflow"},
      {"map_1e400", kShortLog + file("m.json", R"({"segments": [[0, 0, 1e400, 1]]})"),
       "match --map {d}/m.json --log {d}/l.clf", 2, "number overflow"},
      {"rules_1e400",
       kReport + file("rules.json", R"({"accuracy": [{"match": "*", "max_relative_worsening": 1e400}]})"),
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 2, "rules.json"},
      {"report_1e400", kReport + "sed -i 's/\"mean\": [-0-9.e]*/\"mean\": 1e400/' '{d}/r.json'",
       "gate {d}/r.json --baseline {d}/r.json", 2, "number overflow"},
      {"shard_1e400", "mkdir -p '{d}/s' && echo '{\"schema\": 1e400}' > '{d}/s/x.shard-1-of-1.json'",
       "merge {d}/s -o {d}/m", 2, "number overflow"},
      {"options_1e400", kShortLog + file("o.json", R"({"mcl": {"particles": 1e400}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2, "o.json"},
      {"config_1e400", file("c.json", R"({"odometry/sim_corridor": {"runs": 1e400}})"),
       "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2, "c.json"},
      {"set_1e400", "", "run odometry/sim_corridor --set runs=1e400 --out {d}/out", 2, "--set"},
      {"options_is_a_folder", kShortLog + "mkdir '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2, "is a folder"},
      {"config_is_a_folder", "mkdir '{d}/c.json'", "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2,
       "is a folder"},
      {"rules_is_a_folder", kReport + "mkdir '{d}/rules.json'",
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 2, "is a folder"},
      {"false_alarm_1e_minus_300", "", "diagnose {src}/examples/table_3_1_histogram.json --false-alarm 1e-300", 2,
       "--false-alarm"},
      {"wheelbase_1e_minus_320",
       kShortLog + "sed -i 's/^PARAM robot_wheelbase .*/PARAM robot_wheelbase 1e-320/' '{d}/l.clf'",
       "diagnose {d}/l.clf", 2, "robot_wheelbase"},
      {"encoder_ticks_int64_min_diagnose",
       kShortLog + "awk '/^ENCODER/ && !done {$2=\"-9223372036854775808\"; done=1} {print}' '{d}/l.clf' > '{d}/m.clf'",
       "diagnose {d}/m.clf", 2, "64-bit"},
      {"encoder_ticks_int64_min_calibrate",
       kShortLog + "awk '/^ENCODER/ && !done {$2=\"-9223372036854775808\"; done=1} {print}' '{d}/l.clf' > '{d}/m.clf'",
       "calibrate ml {d}/m.clf", 2, "64-bit"},
      {"shard_value_of_wrong_type",
       "mkdir -p '{d}/s' && {exe} run slip/normality_table_3_1 --shard 1/1 --out '{d}/s' >/dev/null 2>&1 && "
       "sed -i 's/\"tasks\": *\\([0-9]*\\)/\"tasks\": \"\\1\"/' '{d}/s/slip/normality_table_3_1.shard-1-of-1.json'",
       "merge {d}/s -o {d}/m", 2, "not a valid shard"},
      {"shard_1e12_tasks",
       "mkdir -p '{d}/s' && {exe} run slip/normality_table_3_1 --shard 1/1 --out '{d}/s' >/dev/null 2>&1 && "
       "sed -i 's/\"tasks\": *\\([0-9]*\\)/\"tasks\": 1000000000000/' "
       "'{d}/s/slip/normality_table_3_1.shard-1-of-1.json'",
       "merge {d}/s -o {d}/m", 2, "not a valid shard"},
      {"run_out_onto_a_file", "touch '{d}/f'", "run odometry/sim_corridor --runs 1 --out {d}/f", 2, "not a folder"},
      {"report_gnuplot_temp_unwritable", "{exe} run odometry/sim_corridor --runs 1 --out '{d}/o' >/dev/null 2>&1",
       "report {d}/o -o {d}/p.html", 2, "temporary folder", "TMPDIR='{d}/no/such/tmp'"},
      // 8. The README's example works.
      {"readme_simulate_then_diagnose", "{exe} simulate corridor --seed 7 -o '{d}/c.clf.gz' >/dev/null 2>&1",
       "diagnose {d}/c.clf.gz", 0, "verdict:"},
      // 9. Garbage is refused.
      {"calibrate_wheelbase_nan",
       kShortLog + "sed -i 's/^PARAM robot_wheelbase .*/PARAM robot_wheelbase nan/' '{d}/l.clf'",
       "calibrate ml {d}/l.clf", 2, "robot_wheelbase"},
      {"calibrate_wheelbase_zero",
       kShortLog + "sed -i 's/^PARAM robot_wheelbase .*/PARAM robot_wheelbase 0/' '{d}/l.clf'",
       "calibrate ml {d}/l.clf", 2, "robot_wheelbase"},
      {"calibrate_wheelbase_negative",
       kShortLog + "sed -i 's/^PARAM robot_wheelbase .*/PARAM robot_wheelbase -0.3/' '{d}/l.clf'",
       "calibrate ml {d}/l.clf", 2, "robot_wheelbase"},
      {"calibrate_denormal_meters_per_tick",
       kShortLog +
           "sed -i 's/^PARAM robot_meters_per_tick_left .*/PARAM robot_meters_per_tick_left 1e-310/' '{d}/l.clf'",
       "calibrate ml {d}/l.clf", 2, "robot_meters_per_tick_left"},
      {"calibrate_all_equal_timestamps",
       kShortLog + "awk '/^ENCODER/ {$4=\"5\"; $6=\"5\"} {print}' '{d}/l.clf' > '{d}/eq.clf'",
       "calibrate ml {d}/eq.clf", 2, "same time"},
      {"run_with_an_empty_data_folder_fails", "mkdir -p '{d}/data'",
       "run odometry/real_logs --data {d}/data --out {d}/out", 2, "skipped for missing data"},
      {"run_skipping_missing_data_by_name", "mkdir -p '{d}/data'",
       "run odometry/real_logs --data {d}/data --skip-missing all --out {d}/out", 0, "wrote"},
      {"run_with_missing_data_folder", "", "run odometry/real_logs --data /typo --out {d}/out", 2, "--data"},
      {"odometry_real_logs_with_a_missing_users_log", "", "run odometry/real_logs --log {d}/absent.clf --out {d}/out",
       2, "absent.clf"},
      {"laser_real_logs_with_a_missing_users_log", "", "run laser/real_logs --log {d}/absent.clf --out {d}/out", 2,
       "absent.clf"},
      {"diagnosis_real_logs_with_a_missing_users_log", "", "run diagnosis/real_logs --log {d}/absent.clf --out {d}/out",
       2, "absent.clf"},
      {"diagnosis_sim_to_real_with_a_missing_users_log", "",
       "run diagnosis/sim_to_real --log {d}/absent.clf --out {d}/out", 2, "absent.clf"},
      {"global_real_logs_with_a_missing_users_log", "", "run global/real_logs --log {d}/absent.clf --out {d}/out", 2,
       "absent.clf"},
      {"noise_real_logs_with_a_missing_users_log", "", "run noise/real_logs --log {d}/absent.clf --out {d}/out", 2,
       "absent.clf"},
      {"landmark_map_with_nan", kShortLog + file("m.txt", "6 0 nan"),
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --out {d}/out", 2, "m.txt:1: y:"},
      {"landmark_map_with_a_repeated_id", kShortLog + file("m.txt", "6 0 0\n6 1 1"),
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --out {d}/out", 2,
       "m.txt:2: id: 6 is listed twice"},
      {"landmark_observation_of_an_id_not_in_the_map", kShortLog + file("m.txt", "6 0 0") + file("o.txt", "5 7 1 0"),
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --landmark-observations {d}/o.txt --out "
       "{d}/out",
       2, "o.txt:1: id: 7 is not a landmark"},
      {"landmark_observation_before_the_first_odometry", kShortLog + file("m.txt", "6 0 0") + file("o.txt", "-1 6 1 0"),
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --landmark-observations {d}/o.txt --out "
       "{d}/out",
       2, "o.txt:1: time: -1 before the first odometry record"},
      {"landmark_observations_without_a_map", kShortLog + file("o.txt", "5 6 1 0"),
       "run odometry/real_logs --log {d}/l.clf --landmark-observations {d}/o.txt --out {d}/out", 2,
       "need a landmark map"},
      {"landmark_map_is_a_folder", kShortLog + "mkdir -p '{d}/m'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m --out {d}/out", 2,
       "is a folder: expected the landmark map to be a regular file"},
      {"landmark_map_without_log", file("m.txt", "6 0 0"),
       "run odometry/real_logs --landmark-map {d}/m.txt --out {d}/out", 2, "need --log"},
      {"mrclam_folder_with_a_robot_it_lacks", "mkdir -p '{d}/M' && printf '1 0 0\\n' > '{d}/M/Robot1_Odometry.dat'",
       "run odometry/real_logs --log {d}/M#robot2 --out {d}/out", 2, "Robot2_Odometry.dat"},
      {"gate_schema_invalid_report",
       kReport + "sed -i 's/\"better\": \"[a-z_]*\"/\"better\": \"sideways\"/' '{d}/r.json'",
       "gate {d}/r.json --baseline {d}/r.json", 2, "not a valid locbench report"},
      {"gate_empty_baseline",
       kReport + "sed -e ':a;N;$!ba' -e 's/\"results\": \\[.*\\],\\n  \"schema\"/\"results\": [],\\n  \"schema\"/' "
                 "'{d}/r.json' > '{d}/empty.json'",
       "gate {d}/r.json --baseline {d}/empty.json", 2, "holds no results"},
      {"gate_empty_rules", kReport + file("rules.json", R"({"accuracy": []})"),
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 2, "checks nothing"},
      {"gate_rule_without_results",
       kReport + file("rules.json", R"({"accuracy": [{"match": "odometry/real_logs:*"}]})"),
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 1, "no current result matches this rule"},
      {"gz_log_with_trailing_garbage",
       kShortLog + "gzip -c '{d}/l.clf' > '{d}/g.clf.gz' && printf 'GARBAGE' >> '{d}/g.clf.gz'",
       "diagnose {d}/g.clf.gz", 2, "trailing garbage"},
      {"gz_log_of_two_members_is_fine",
       kShortLog +
           "head -n 5 '{d}/l.clf' | gzip -c > '{d}/g.clf.gz' && tail -n +6 '{d}/l.clf' | gzip -c >> '{d}/g.clf.gz'",
       "calibrate ml {d}/g.clf.gz", 0, "converged"},
      {"map_from_log_nan", kShortLog, "localize --map-from-log nan --log {d}/l.clf", 2, "--map-from-log"},
      // 10. Messages that say what is wrong.
      {"config_wrong_type_names_the_file", file("c.json", R"({"odometry/sim_corridor": {"runs": "many"}})"),
       "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2, "c.json"},
      {"options_wrong_type_names_the_file", kShortLog + file("o.json", R"({"mcl": {"particles": "many"}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2, "o.json"},
      {"missing_scenario_file", "", "simulate {d}/x.json -o {d}/o.clf", 2, "no such scenario file"},
      {"world_file_relative_to_the_scenario",
       "mkdir -p '{d}/sub' && cp '{src}/examples/room_map.json' '{d}/sub/room.json' && " +
           file(
               "sub/s.json",
               R"({"preset": "corridor", "world": {"kind": "file", "file": "room.json"}, "motion": {"kind": "straight", "distance": 0.5}})"),
       "simulate {d}/sub/s.json -o {d}/o.clf", 0, "wrote"},
      // 11. Fail closed: a failed case is a failed run, a gate cannot be fooled, no
      // input is overwritten, every flag is used or refused, nonsense is not a result.
      {"run_with_a_corrupt_catalog_log_exits_1",
       "mkdir -p '{d}/data/slam_benchmark/clf' && echo garbage | gzip > "
       "'{d}/data/slam_benchmark/clf/aces.from_bag.clf.gz'",
       "run odometry/real_logs --data {d}/data --skip-missing all --out {d}/out", 1, "odometry/aces"},
      {"run_with_a_missing_mrclam_file_exits_1", "mkdir -p '{d}/data/mrclam/MRCLAM_Dataset6'",
       "run odometry/real_logs --data {d}/data --skip-missing all --out {d}/out", 1, "case(s) failed"},
      {"run_log_without_relations_exits_1", kShortLog, "run laser/real_logs --log {d}/l.clf --out {d}/out", 1,
       "no relation pairs two scans"},
      {"run_header_only_tum_exits_1", kShortLog + "printf '# timestamp tx ty tz qx qy qz qw\\n' > '{d}/h.tum'",
       "run odometry/real_logs --log {d}/l.clf --ground-truth {d}/h.tum --out {d}/out", 1, "case(s) failed"},
      {"run_skipping_missing_data_lists_the_skips", "mkdir -p '{d}/data'",
       "run odometry/real_logs --data {d}/data --skip-missing all --out {d}/out", 0, "accepted by --skip-missing"},
      {"run_config_inside_its_out_folder", "mkdir -p '{d}/o/slip' && echo '{}' > '{d}/o/slip/normality_table_3_1.json'",
       "run slip/normality_table_3_1 --config {d}/o/slip/normality_table_3_1.json --out {d}/o", 2,
       "inside the folder --out"},
      {"run_relations_inside_its_out_folder", kShortLog + "mkdir -p '{d}/o' && touch '{d}/o/r.relations'",
       "run odometry/real_logs --log {d}/l.clf --relations {d}/o/r.relations --out {d}/o", 2,
       "inside the folder --out"},
      {"merge_into_a_folder_run_is_writing",
       "mkdir -p '{d}/s' '{d}/o' && touch '{d}/o/.locbench.lock' && {exe} run slip/normality_table_3_1 --shard 1/1 "
       "--out '{d}/s' >/dev/null 2>&1",
       "merge {d}/s -o {d}/o/slip/normality_table_3_1.json", 2, "in use", "flock '{d}/o/.locbench.lock'"},
      {"merge_folder_lock_file_is_a_symlink",
       "mkdir -p '{d}/s' '{d}/o' && ln -s '{d}/elsewhere' '{d}/o/.locbench.lock' && {exe} run "
       "slip/normality_table_3_1 --shard 1/1 --out '{d}/s' >/dev/null 2>&1",
       "merge {d}/s -o {d}/o", 2, "symbolic link"},
      {"run_lock_file_is_a_symlink", "mkdir -p '{d}/out' && ln -s '{d}/elsewhere' '{d}/out/.locbench.lock'",
       "run odometry/sim_corridor --runs 1 --out {d}/out && test ! -e '{d}/elsewhere'", 2, "symbolic link"},
      {"run_removes_a_killed_writers_temporary",
       "mkdir -p '{d}/out/odometry' && touch -d '1 hour ago' '{d}/out/odometry/.sim_corridor.json.tmp-AbCdEf'",
       "run odometry/sim_corridor --runs 1 --out {d}/out >/dev/null && test ! -e "
       "'{d}/out/odometry/.sim_corridor.json.tmp-AbCdEf' && echo no-temporary-left",
       0, "no-temporary-left"},
      {"simulate_removes_a_killed_writers_temporary", "touch -d '1 hour ago' '{d}/.c.clf.tmp-AbCdEf'",
       "simulate corridor -o {d}/c.clf >/dev/null && test ! -e '{d}/.c.clf.tmp-AbCdEf' && echo no-temporary-left", 0,
       "no-temporary-left"},
      {"calibrate_ml_relations_on_a_catalog_dataset", "", "calibrate ml aces --relations /nonexistent", 2,
       "--relations"},
      {"calibrate_ml_relations_file_missing", kShortLog, "calibrate ml {d}/l.clf --relations {d}/absent.relations", 2,
       "absent.relations"},
      {"calibrate_umbmark_with_relations", "",
       "calibrate umbmark-classic {src}/examples/umbmark_trilobot.json --relations /nonexistent", 2,
       "applies to `calibrate ml`"},
      {"calibrate_ml_data_on_a_log_file", kShortLog, "calibrate ml {d}/l.clf --data /tmp", 2, "--data"},
      {"calibrate_ml_negative_wheelbase_is_not_converged",
       "{exe} simulate corridor --seed 7 -o '{d}/c.clf' >/dev/null 2>&1", "calibrate ml {d}/c.clf", 1, "is impossible"},
      {"gate_zero_ns_speed_pair", speed_ratio_gate("0", "0"),
       "gate {d}/c.json --baseline {d}/b.json --rules {d}/rules.json", 1, "≤ 0 ns"},
      {"gate_negative_ns_times", speed_ratio_gate("-50", "100"),
       "gate {d}/c.json --baseline {d}/b.json --rules {d}/rules.json", 1, "≤ 0 ns"},
      {"gate_values_contradicting_the_mean",
       "{exe} run odometry/sim_corridor --runs 3 --out '{d}/b' >/dev/null 2>&1 && cp -r '{d}/b' '{d}/c' && "
       "sed -i '0,/\"mean\": [-0-9.e]*/s//\"mean\": 0.001/' '{d}/c/odometry/sim_corridor.json'",
       "gate {d}/c --baseline {d}/b", 1, "contradicts its `values`"},
      {"gate_negative_position_error",
       "{exe} run odometry/sim_corridor --runs 3 --out '{d}/b' >/dev/null 2>&1 && mkdir -p '{d}/c/odometry' && " +
           std::string(R"AWK(awk '/"values": \[/ {skip = 1} skip {if (/\]/) skip = 0; next} )AWK"
                       R"AWK(/"(mean|median|min|max)": [0-9]/ {sub(/": /, "\": -")} {print}' )AWK") +
           "'{d}/b/odometry/sim_corridor.json' > '{d}/c/odometry/sim_corridor.json'",
       "gate {d}/c --baseline {d}/b", 1, "cannot be negative"},
      {"gate_folder_of_two_run_ids",
       "{exe} run odometry/sim_corridor slip/normality_table_3_1 --runs 3 --out '{d}/b' >/dev/null 2>&1 && cp -r "
       "'{d}/b' '{d}/c' && sed -i 's/\"run_id\": \"[^\"]*\"/\"run_id\": \"an-older-run\"/' "
       "'{d}/c/odometry/sim_corridor.json'",
       "gate {d}/c --baseline {d}/b", 1, "mixes runs"},
      {"report_says_a_folder_mixes_two_runs",
       "{exe} run odometry/sim_corridor slip/normality_table_3_1 --runs 3 --out '{d}/b' >/dev/null 2>&1 && sed -i "
       "'s/\"run_id\": \"[^\"]*\"/\"run_id\": \"an-older-run\"/' '{d}/b/odometry/sim_corridor.json'",
       "report {d}/b -o {d}/p.html", 0, "mixes the reports of 2 runs"},
      {"gate_skip_missing_all_against_the_committed_baseline",
       "mkdir -p '{d}/data' && {exe} run odometry/real_logs --data '{d}/data' --skip-missing all --out '{d}/c' "
       ">/dev/null 2>&1",
       "gate {d}/c --baseline {src}/benchmarks/reference_results/default/odometry/real_logs.json", 1,
       "none was compared"},

      // 12. One input opener: a regular file or an error naming what it is, never a
      // blocked open or a read without end; bytes capped (decompressed too), JSON nesting capped.
      {"fifo_as_scenario", "mkfifo '{d}/s.json'", "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: is a named pipe (FIFO): expected the JSON file to be a regular file"},
      {"fifo_as_log", "mkfifo '{d}/l.clf'", "diagnose {d}/l.clf", 2, "l.clf: is a named pipe (FIFO)"},
      {"fifo_as_gzip_log", "mkfifo '{d}/l.clf.gz'", "diagnose {d}/l.clf.gz", 2, "is a named pipe (FIFO)"},
      {"fifo_as_rules", kReport + "mkfifo '{d}/rules.json'",
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 2,
       "rules.json: is a named pipe (FIFO): expected the rules file (JSON)"},
      {"fifo_as_baseline", kReport + "mkfifo '{d}/b.json'", "gate {d}/r.json --baseline {d}/b.json", 2,
       "b.json: is a named pipe (FIFO)"},
      {"fifo_as_config", "mkfifo '{d}/c.json'", "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2,
       "c.json: is a named pipe (FIFO): expected the --config file (JSON)"},
      {"fifo_as_tuple_file", "mkfifo '{d}/t.tuple'", "calibrate ml {d}/t.tuple", 2, "t.tuple: is a named pipe (FIFO)"},
      {"fifo_as_umbmark_input", "mkfifo '{d}/u.json'", "calibrate umbmark-classic {d}/u.json", 2,
       "u.json: is a named pipe (FIFO)"},
      {"fifo_as_line_map", kShortLog + "mkfifo '{d}/m.json'", "localize --map {d}/m.json --log {d}/l.clf", 2,
       "m.json: is a named pipe (FIFO)"},
      {"fifo_as_localize_options", kShortLog + "mkfifo '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: is a named pipe (FIFO)"},
      {"fifo_as_histogram", "mkfifo '{d}/h.json'", "diagnose {d}/h.json", 2, "h.json: is a named pipe (FIFO)"},
      {"fifo_as_relations", kShortLog + "mkfifo '{d}/r.relations'",
       "run odometry/real_logs --log {d}/l.clf --relations {d}/r.relations --out {d}/out", 2,
       "r.relations: is a named pipe (FIFO)"},
      {"fifo_as_landmark_map", kShortLog + "mkfifo '{d}/m.txt'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --out {d}/out", 2,
       "m.txt: is a named pipe (FIFO): expected the landmark map to be a regular file"},
      {"fifo_in_an_mrclam_folder_is_not_a_missing_file",
       "mkdir '{d}/mr' && touch '{d}/mr/Robot1_Odometry.dat' '{d}/mr/Robot1_Measurement.dat' && "
       "mkfifo '{d}/mr/Robot1_Groundtruth.dat'",
       "diagnose '{d}/mr#robot1'", 2, "Robot1_Groundtruth.dat: is a named pipe (FIFO)"},
      {"fifo_nothing_reads_as_simulate_output", file("s.json", R"({"preset": "corridor"})") + "mkfifo '{d}/x.clf'",
       "simulate {d}/s.json -o {d}/x.clf", 2, "x.clf: is a named pipe (FIFO) that nothing reads"},
      {"fifo_nothing_reads_as_report_output", "mkfifo '{d}/r.json'",
       "calibrate umbmark-classic {src}/examples/umbmark_trilobot.json --report {d}/r.json", 2,
       "r.json: is a named pipe (FIFO) that nothing reads"},
      {"dev_zero_as_log", "ln -s /dev/zero '{d}/z.clf'", "diagnose {d}/z.clf", 2, "z.clf: is a character device"},
      {"dev_zero_as_scenario", "ln -s /dev/zero '{d}/z.json'", "simulate {d}/z.json -o {d}/x.clf", 2,
       "z.json: is a character device"},
      {"dev_urandom_as_report", "ln -s /dev/urandom '{d}/z.json'", "gate {d}/z.json --baseline {d}/z.json", 2,
       "z.json: is a character device"},
      {"dev_zero_as_tuple_file", "ln -s /dev/zero '{d}/z.tuple'", "calibrate ml {d}/z.tuple", 2,
       "z.tuple: is a character device"},
      {"sparse_2_gb_log_refused_before_reading", "truncate -s 2G '{d}/big.clf'", "diagnose {d}/big.clf", 2,
       "big.clf: is more than 134217728 bytes"},
      {"log_at_the_byte_cap_is_read",
       "yes '# a comment line of the log, as long as a short scan line' | head -c 134217728 > '{d}/l.clf'",
       "diagnose {d}/l.clf", 2, "no odometry"},
      {"log_one_byte_past_the_byte_cap",
       "yes '# a comment line of the log, as long as a short scan line' | head -c 134217729 > '{d}/l.clf'",
       "diagnose {d}/l.clf", 2, "l.clf: is more than 134217728 bytes"},
      {"gzip_log_decompressing_to_the_cap_is_read",
       "yes '# a comment line of the log, as long as a short scan line' | head -c 134217728 | gzip -1 > "
       "'{d}/l.clf.gz'",
       "diagnose {d}/l.clf.gz", 2, "no odometry"},
      {"gzip_log_decompressing_one_byte_past_the_cap",
       "yes '# a comment line of the log, as long as a short scan line' | head -c 134217729 | gzip -1 > "
       "'{d}/l.clf.gz'",
       "diagnose {d}/l.clf.gz", 2, "l.clf.gz: decompresses to more than 134217728 bytes"},
      {"gzip_bomb_log_stops_at_the_cap", "head -c 300000000 /dev/zero | gzip -1 > '{d}/l.clf.gz'",
       "diagnose {d}/l.clf.gz", 2, "decompresses to more than 134217728 bytes"},
      {"gzip_bomb_tuple_file_stops_at_the_cap", "head -c 300000000 /dev/zero | gzip -1 > '{d}/t.tuple.gz'",
       "calibrate ml {d}/t.tuple.gz", 2, "decompresses to more than 134217728 bytes"},
      {"gzip_bomb_relations_stop_at_the_cap",
       kShortLog + "head -c 300000000 /dev/zero | gzip -1 > '{d}/r.relations.gz'",
       "run odometry/real_logs --log {d}/l.clf --relations {d}/r.relations.gz --out {d}/out", 2,
       "decompresses to more than 134217728 bytes"},
      {"json_at_the_byte_cap_is_read",
       "head -c 33554432 /dev/zero | tr '\\0' ' ' > '{d}/s.json' && printf '%s' '{\"preset\": \"corridor\"}' | dd "
       "of='{d}/s.json' conv=notrunc 2>/dev/null",
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"json_one_byte_past_the_byte_cap",
       "head -c 33554433 /dev/zero | tr '\\0' ' ' > '{d}/s.json' && printf '%s' '{\"preset\": \"corridor\"}' | dd "
       "of='{d}/s.json' conv=notrunc 2>/dev/null",
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: is more than 33554432 bytes"},
      {"sparse_report_past_the_json_cap", "truncate -s 1G '{d}/r.json'", "gate {d}/r.json --baseline {d}/r.json", 2,
       "r.json: is more than 33554432 bytes"},
      {"json_nested_512_deep_is_parsed",
       "{ for i in $(seq 512); do printf '['; done; for i in $(seq 512); do printf ']'; done; } > '{d}/r.json'",
       "gate {d}/r.json --baseline {d}/r.json", 2, "expected a locbench report"},
      {"json_nested_513_deep",
       "{ for i in $(seq 513); do printf '['; done; for i in $(seq 513); do printf ']'; done; } > '{d}/r.json'",
       "gate {d}/r.json --baseline {d}/r.json", 2, "r.json:1: arrays and objects nest more than 512 levels deep"},
      {"report_nested_100000_deep_does_not_crash_gate",
       kReport + "{ sed -n '1,/\"configuration\": {/p' '{d}/r.json'; printf '\"deep\": '; head -c 100000 /dev/zero | "
                 "tr '\\0' '['; head -c 100000 /dev/zero | tr '\\0' ']'; printf ',\\n'; sed '1,/\"configuration\": "
                 "{/d' '{d}/r.json'; } > '{d}/deep.json'",
       "gate {d}/deep.json --baseline {d}/r.json", 2, "deep.json:4: arrays and objects nest more than 512 levels deep"},
      {"report_nested_100000_deep_does_not_crash_report",
       kReport + "mkdir '{d}/o' && { printf '{\"a\": '; head -c 100000 /dev/zero | tr '\\0' '['; head -c 100000 "
                 "/dev/zero | tr '\\0' ']'; printf '}'; } > '{d}/o/r.json'",
       "report {d}/o -o {d}/p.html", 2, "nest more than 512 levels deep"},
      {"config_nested_600_deep",
       "{ for i in $(seq 600); do printf '{\"a\":'; done; printf 1; for i in $(seq 600); do "
       "printf '}'; done; } > '{d}/c.json'",
       "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2, "c.json:1: arrays and objects nest more than"},
      {"brackets_inside_json_strings_are_not_nesting",
       "{ printf '{\"residual\": \"'; head -c 1000 /dev/zero | tr '\\0' '['; printf '\", \"nonsense\": 1}'; } > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "nonsense: unknown key"},
      {"help_states_the_input_caps", "", "--help", 0, "bytes of one input file (decompressed, for gzip) <= 134217728"},
      // 13. Crashes and internal errors: exit 0, or 2 with the reason, never 3.
      {"simulate_180_beams", file("s.json", R"({"preset": "corridor", "laser": {"enabled": true, "beams": 180}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_360_beams", file("s.json", R"({"preset": "corridor", "laser": {"enabled": true, "beams": 360}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_180_beams_reads_back_with_its_bearings",
       file("s.json", R"({"preset": "corridor", "laser": {"enabled": true, "beams": 180}})") +
           "{exe} simulate '{d}/s.json' -o '{d}/x.clf' >/dev/null",
       "match --map {src}/examples/room_map.json --log {d}/x.clf", 0, "eap/x_clf/segments_matched"},
      {"simulate_a_narrow_centred_field_of_view",
       file(
           "s.json",
           R"({"preset": "corridor", "laser": {"enabled": true, "beams": 91, "first_bearing": -0.7854, "last_bearing": 0.7854}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_an_off_centre_field_of_view",
       file("s.json",
            R"({"preset": "corridor", "laser": {"enabled": true, "first_bearing": -1.5, "last_bearing": 0.5}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "laser.first_bearing must be -laser.last_bearing"},
      {"simulate_bearings_in_reverse",
       file("s.json", R"({"preset": "corridor", "laser": {"enabled": true, "first_bearing": 1, "last_bearing": -1}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "laser.last_bearing must be >= laser.first_bearing"},
      {"localize_seed_2_to_the_64_minus_1", kShortLog,
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --seed 18446744073709551615", 2,
       "--seed: Value 18446744073709551615 not in range 0 to 9007199254740991"},
      {"run_seed_not_a_number", "", "run odometry/sim_corridor --seed abc --out {d}/out", 2,
       "--seed: Value abc is not a whole number"},
      {"simulate_seed_with_a_fraction", "", "simulate corridor --seed 1.5 -o {d}/x.clf", 2,
       "--seed: Value 1.5 is not a whole number"},
      {"localize_negative_seed", kShortLog, "localize --map {src}/examples/room_map.json --log {d}/l.clf --seed -5", 2,
       "--seed: Value -5 not in range"},
      {"simulate_negative_seed_is_not_wrapped", file("s.json", R"({"preset": "corridor"})"),
       "simulate {d}/s.json --seed -5 -o {d}/x.clf", 2, "--seed: Value -5 not in range"},
      {"simulate_seed_at_the_json_safe_limit", file("s.json", R"({"preset": "corridor"})"),
       "simulate {d}/s.json --seed 9007199254740991 -o {d}/x.clf", 0, "seed 9007199254740991"},
      {"simulate_seed_past_the_json_safe_limit", file("s.json", R"({"preset": "corridor"})"),
       "simulate {d}/s.json --seed 9007199254740992 -o {d}/x.clf", 2, "not in range 0 to 9007199254740991"},
      {"dataset_name_with_dot_dot_slash",
       kShortLog + file("c.json",
                        R"({"odometry/real_logs": {"datasets": [{"name": "../../../tmp/evil", "log": "{d}/l.clf"}]}})"),
       "run odometry/real_logs --config {d}/c.json --out {d}/out", 2,
       "dataset name \"../../../tmp/evil\": expected letters, digits and _ - . : + only"},
      {"dataset_name_with_a_slash",
       kShortLog + file("c.json", R"({"odometry/real_logs": {"datasets": [{"name": "a/b", "log": "{d}/l.clf"}]}})"),
       "run odometry/real_logs --config {d}/c.json --out {d}/out", 2, "dataset name \"a/b\""},
      {"calibrate_ml_one_tuple",
       file("t.tuple", R"({ "T": 0.79, "phi_l": 0.14, "phi_r": -0.137, "sm": [ 0.0011, -0.0005, -0.0275 ] })"),
       "calibrate ml {d}/t.tuple", 2, "t.tuple: 1 samples give 3 measurements for 6 free parameters"},
      {"calibrate_ml_tuples_without_motion",
       "for i in 1 2 3 4 5 6 7 8 9 10; do echo '{ \"T\": 1, \"phi_l\": 0, \"phi_r\": 0, \"sm\": [0, 0, 0] }'; done > "
       "'{d}/t.tuple'",
       "calibrate ml {d}/t.tuple", 2, "t.tuple: 0 samples give 0 measurements for 6 free parameters after outlier"},
      {"mcl_a_billion_particles", kShortLog + file("o.json", R"({"mcl": {"initial_particles": 1000000000}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "MclOptions.initial_particles: expected a number in [1, 1000000], got 1000000000"},
      {"mcl_particles_at_the_limit_for_one_update",
       kShortLog +
           file("o.json",
                R"({"mcl": {"initial_particles": 1000000, "max_particles": 1000000, "update_min_distance": 1e9}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 0, "mcl/"},
      {"mcl_max_particles_past_the_limit", kShortLog + file("o.json", R"({"mcl": {"max_particles": 1000001}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "MclOptions.max_particles: expected a number in [1, 1000000]"},
      {"grid_markov_cells_past_the_limit", kShortLog + file("o.json", R"({"grid_markov": {"max_cells": 1e12}})"),
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "GridMarkovOptions.max_cells: expected a number in [1, 10000000]"},
      // 15. Limits that mean fast: a row at each limit and one past it. The at-limit
      // inputs too slow for the sanitizer build are timed by scripts/time_limits.sh instead.
      {"histogram_500_filled_bins_at_the_limit", kHist500, "diagnose {d}/h.json", 0, "verdict:"},
      {"histogram_501_filled_bins", kHist500 + "sed -i 's/\"counts\": \\[/\"counts\": [1,/; s/,0\\]}/]}/' '{d}/h.json'",
       "diagnose {d}/h.json", 2, "counts (bins > 0): 501 exceeds the limit 500"},
      {"histogram_total_count_at_the_limit",
       file(
           "h.json",
           R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[1000000,2000000,4000000,2000000,1000000]})"),
       "diagnose {d}/h.json", 0, "verdict:"},
      {"histogram_total_count_past_the_limit",
       file(
           "h.json",
           R"({"residual":"r","unit":"deg","edges":[0,1,2,3,4,5],"counts":[1000000,2000000,4000001,2000000,1000000]})"),
       "diagnose {d}/h.json", 2, "counts (their sum): 1e+07 exceeds the limit 10000000"},
      {"diagnose_odometry_records_at_the_limit", encoder_log(30000), "diagnose {d}/e.clf", 2, "e.clf"},
      {"diagnose_odometry_records_past_the_limit", encoder_log(30001), "diagnose {d}/e.clf", 2,
       "odometry records (ENCODER, ODOM): 30001 exceeds the limit 30000"},
      {"diagnose_max_records_raises_the_limit", encoder_log(30001), "diagnose {d}/e.clf --max-records 30001", 2,
       "e.clf"},
      {"diagnose_max_records_0", encoder_log(10), "diagnose {d}/e.clf --max-records 0", 2, "--max-records: Value 0"},
      {"simulate_records_at_the_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "encoders": {"rate": 1000}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_records_past_the_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "encoders": {"rate": 1001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "duration x encoders.rate: 1.001e+06 exceeds the limit 1000000"},
      {"simulate_truth_records_past_the_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "truth": {"rate": 1001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "duration x truth.rate: 1.001e+06 exceeds the limit 1000000"},
      {"simulate_laser_ranges_at_the_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "laser": {"enabled": true, "rate": 2, "beams": 1000}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_laser_ranges_past_the_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "laser": {"enabled": true, "rate": 2, "beams": 1001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "duration x laser.rate x laser.beams: 2.002e+06 exceeds the limit 2000000"},
      {"match_laser_ranges_at_the_limit", scan_log(200, 10000),
       "match --map {src}/examples/room_map.json --log {d}/s.clf", 0, "segments_matched"},
      {"match_laser_ranges_past_the_limit", scan_log(201, 10000),
       "match --map {src}/examples/room_map.json --log {d}/s.clf", 2,
       "laser ranges (201 scans): 2.01e+06 exceeds the limit 2000000"},
      {"localize_laser_ranges_past_the_limit", scan_log(201, 10000),
       "localize --map {src}/examples/room_map.json --log {d}/s.clf", 2, "laser ranges (201 scans)"},
      {"agglomerative_beams_squared_past_the_limit", scan_log(3, 10000),
       "match --map {src}/examples/room_map.json --log {d}/s.clf --matcher agglomerative", 2,
       "agglomerative is quadratic in them): 3e+08 exceeds the limit 200000000"},
      {"mcl_work_past_the_limit",
       kShortLog +
           file(
               "o.json",
               R"({"mcl": {"initial_particles": 1000000, "max_particles": 1000000, "kld": false, "update_min_distance": 0, "update_min_angle": 0}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "mcl: at least 1000000 particles x (20 beams + 80) over 23 updates (max_particles after the first, no KLD)"},
      {"mcl_tiny_kld_bin_stops_at_the_work_limit",
       kShortLog +
           file(
               "o.json",
               R"({"mcl": {"max_particles": 1000000, "field": {"beams": 200}, "kld_bin": [0.0001, 0.0001, 0.0001], "update_min_distance": 0, "update_min_angle": 0}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "particle-beams done after"},
      {"mcl_tiny_kld_bin_within_the_work_limit",
       kShortLog + file("o.json", R"({"mcl": {"max_particles": 100000, "kld_bin": [0.0001, 0.0001, 0.0001]}})"),
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 0, "mcl/"},
      {"grid_markov_1_cm_cells", kShortLog + file("o.json", R"({"grid_markov": {"cell_size": 0.01}})"),
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "cells exceed max_cells"},
      {"grid_markov_cells_near_the_limit_one_update",
       kShortLog + file("o.json", R"({"grid_markov": {"cell_size": 0.03, "update_min_distance": 1e9}})"),
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 0,
       "grid_markov/"},
      {"grid_markov_work_past_the_limit",
       kShortLog +
           file("o.json", R"({"grid_markov": {"cell_size": 0.03, "update_min_distance": 0, "update_min_angle": 0}})"),
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "exceeds the limit 800000000"},
      {"landmark_map_at_the_limit",
       kShortLog + "awk 'BEGIN{for(i=1;i<=10000;i++) printf \"%d %d %d\\n\", i, i % 100, i / 100}' > '{d}/m.txt'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --out {d}/out", 1, "failed"},
      {"landmark_map_past_the_limit",
       kShortLog + "awk 'BEGIN{for(i=1;i<=10001;i++) printf \"%d %d %d\\n\", i, i % 100, i / 100}' > '{d}/m.txt'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --out {d}/out", 2,
       "landmarks: 10001 exceeds the limit 10000"},
      {"landmark_observations_at_the_limit",
       kShortLog + file("m.txt", "6 0 0") +
           "awk 'BEGIN{for(i=0;i<200000;i++) printf \"%.5f 6 1.5 0.2\\n\", 0.1 + i * 0.0002}' > '{d}/o.txt'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --landmark-observations {d}/o.txt --out "
       "{d}/out",
       1, "failed"},
      {"landmark_observations_past_the_limit",
       kShortLog + file("m.txt", "6 0 0") +
           "awk 'BEGIN{for(i=0;i<200001;i++) printf \"%.5f 6 1.5 0.2\\n\", 0.1 + i * 0.0002}' > '{d}/o.txt'",
       "run odometry/real_logs --log {d}/l.clf --landmark-map {d}/m.txt --landmark-observations {d}/o.txt --out "
       "{d}/out",
       2, "exceeds the limit 200000"},
      {"run_runs_past_the_limit", "", "run odometry/sim_corridor --runs 1001 --out {d}/out", 2,
       "--runs: Value 1001 not in range 1 to 1000"},
      {"run_set_runs_past_the_limit", "", "run odometry/sim_corridor --set runs=1001 --out {d}/out", 2,
       "runs: 1001 exceeds the limit 1000"},
      {"help_states_the_work_limits", "", "--help", 0,
       "grid_markov: cells x (field.beams + 10) x updates <= 800000000"},
      {"help_states_the_filled_bins_limit", "", "--help", 0, "histogram bins holding samples (counts > 0) <= 500"},
      // 14. Usability.
      {"threads_0_names_the_range", "", "run odometry/sim_corridor --threads 0 --out {d}/out", 2,
       "--threads: Value 0 not in range 1 to 1024"},
      {"threads_past_the_limit", "", "run odometry/sim_corridor --threads 1025 --out {d}/out", 2,
       "not in range 1 to 1024"},
      {"merge_threads_0", "mkdir '{d}/s'", "merge {d}/s -o {d}/o --threads 0", 2, "not in range 1 to 1024"},
      {"unknown_subcommand", "", "frobnicate", 2, "unknown subcommand 'frobnicate': expected one of list, simulate"},
      // 16. Every limit of simulate, match and localize past its value (and the likelihood
      // field's), options out of range, a tracker without a start.
      {"simulate_physics_steps_past",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "physics": {"step": 0.0000499}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: duration / physics.step: 2.00401e+07 exceeds the limit 20000000"},
      {"simulate_duration_past",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 5001}, "drive": {"speed": 0.5, "pause": 0}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: the motion's duration (legs / drive.speed, turns / drive.turn_rate, pauses):"},
      {"simulate_side_past", file("s.json", R"({"preset": "corridor", "motion": {"kind": "umbmark", "side": 10001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: motion.side: 10001 exceeds the limit 10000"},
      {"simulate_start_past", file("s.json", R"({"preset": "corridor", "start": [10001, 0, 0]})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: start: 10001 exceeds the limit 10000"},
      {"simulate_world_segment_past",
       file("s.json", R"({"preset": "corridor", "world": {"segments": [[0, 0, 10001, 0]]}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: world.segments[0]: 10001 exceeds the limit 10000"},
      {"simulate_beams_at_limit",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1.0}, "laser": {"enabled": true, "beams": 10000}})"),
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_beams_past",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1.0}, "laser": {"enabled": true, "beams": 10001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: laser.beams: 10001 exceeds the limit 10000"},
      {"simulate_runs_past",
       file("s.json", R"({"preset": "corridor", "motion": {"kind": "umbmark", "runs": 1001, "side": 1}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: motion.runs: 1001 exceeds the limit 1000"},
      {"simulate_compass_rate_past",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "compass": {"rate": 1001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: duration x compass.rate: 1.001e+06 exceeds the limit 1000000"},
      {"simulate_trajectory_rate_past",
       file(
           "s.json",
           R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 1000}, "drive": {"speed": 1, "pause": 0}, "physics": {"trajectory_rate": 1001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: duration x physics.trajectory_rate: 1.001e+06 exceeds the limit 1000000"},
      {"simulate_distance_past",
       file("s.json", R"({"preset": "corridor", "motion": {"kind": "straight", "distance": 10001}})"),
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: motion.distance: 10001 exceeds the limit 10000"},
      {"match_one_scan_at_beam_limit",
       "awk 'BEGIN{printf \"FLASER 10000\"; for(i=0;i<10000;i++) printf \" 1.5\"; print \" 2 2 0.3 2 2 0.3 1.0 h "
       "1.0\"}' > '{d}/s.clf'",
       "match --map {src}/examples/room_map.json --log {d}/s.clf", 0, "eap/s_clf/"},
      {"match_unknown_matcher", kShortLog, "match --map {src}/examples/room_map.json --log {d}/l.clf --matcher hough",
       2, "unknown matcher 'hough' (known: eap, eap_indexed, split_and_merge, agglomerative, rwht)"},
      {"match_log_without_scans", kShortLog + "grep -v FLASER '{d}/l.clf' > '{d}/n.clf'",
       "match --map {src}/examples/room_map.json --log {d}/n.clf", 2,
       "n.clf: laser scans (FLASER/ROBOTLASER records); the log has none"},
      {"match_empty_map", kShortLog + "echo '{\"name\": \"e\", \"segments\": []}' > '{d}/m.json'",
       "match --map {d}/m.json --log {d}/l.clf", 2, "m.json: a map with at least one segment"},
      {"match_map_segment_nan", kShortLog + "echo '{\"name\": \"e\", \"segments\": [[0, 0, NaN, 1]]}' > '{d}/m.json'",
       "match --map {d}/m.json --log {d}/l.clf", 2,
       "m.json:1: 'NaN' is not a JSON number: NaN and Infinity are not allowed; every value must"},
      {"match_map_segment_of_three_numbers",
       kShortLog + "echo '{\"name\": \"e\", \"segments\": [[0, 0, 1]]}' > '{d}/m.json'",
       "match --map {d}/m.json --log {d}/l.clf", 2,
       "m.json: segments[0]: expected an array of 4 numbers, found an array of 3"},
      {"match_map_zero_length_segment",
       kShortLog + "echo '{\"name\": \"e\", \"segments\": [[1, 1, 1, 1]]}' > '{d}/m.json'",
       "match --map {d}/m.json --log {d}/l.clf", 2, "m.json: segments[0]: zero-length segment"},
      {"localize_start_two_numbers", kShortLog,
       "localize --method ekf_eap --map {src}/examples/room_map.json --log {d}/l.clf --start 1,2", 2,
       "--start: expected X,Y,THETA in metres and radians, got '1,2'"},
      {"localize_start_nan", kShortLog,
       "localize --method ekf_eap --map {src}/examples/room_map.json --log {d}/l.clf --start nan,1,0", 2,
       "--start: expected X,Y,THETA in metres and radians, got 'nan,1,0'"},
      {"localize_map_and_map_from_log", kShortLog,
       "localize --map {src}/examples/room_map.json --map-from-log 2 --log {d}/l.clf", 2,
       "give exactly one of --map FILE and --map-from-log SECONDS"},
      {"localize_neither_map", kShortLog, "localize --log {d}/l.clf", 2,
       "give exactly one of --map FILE and --map-from-log SECONDS"},
      {"localize_map_from_log_negative", kShortLog, "localize --map-from-log -1 --log {d}/l.clf", 2,
       "--map-from-log -1: expected a duration in (0, 1e6] s"},
      {"localize_unknown_method", kShortLog, "localize --method ukf --map {src}/examples/room_map.json --log {d}/l.clf",
       2, "unknown localization method 'ukf' (known: mcl, grid_markov, ekf_eap,"},
      {"localize_tracker_without_start",
       "awk 'BEGIN{for(s=0;s<5;s++){printf \"FLASER 181\"; for(i=0;i<181;i++) printf \" 1.5\"; printf \" 2 2 0.3 2 2 "
       "0.3 %.1f h %.1f\\n\", s*0.2, s*0.2}}' > '{d}/s.clf'",
       "localize --method ekf_eap --map {src}/examples/room_map.json --log {d}/s.clf", 2,
       "ekf_eap tracks from a known start: give --start X,Y,THETA (the log has no TRUEPOS)"},
      {"localize_options_unknown_method_key", kShortLog + "echo '{\"ukf\": {}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: configuration: unknown option ukf"},
      {"grid_cell_size_zero", kShortLog + "echo '{\"grid_markov\": {\"cell_size\": 0}}' > '{d}/o.json'",
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: GridMarkovOptions.cell_size: expected > 0 m, got 0.0"},
      {"grid_angular_cell_past_pi", kShortLog + "echo '{\"grid_markov\": {\"angular_cell\": 4}}' > '{d}/o.json'",
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: GridMarkovOptions.angular_cell: expected a number in (0, 3.141592653589793] rad,"},
      {"mcl_kld_bin_negative", kShortLog + "echo '{\"mcl\": {\"kld_bin\": [-1, 0.1, 0.1]}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: MclOptions.kld_bin: expected each > 0 m, m, rad, got [-1.0,0.1,0.1]"},
      {"mcl_min_particles_above_max",
       kShortLog + "echo '{\"mcl\": {\"min_particles\": 5000, \"max_particles\": 100}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: MclOptions: need min_particles ≤ max_particles"},
      {"mcl_alpha_fast_zero", kShortLog + "echo '{\"mcl\": {\"alpha_fast\": 0}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: MclOptions.alpha_fast: expected a number in (0, 1], got 0.0"},
      {"mcl_field_beams_zero", kShortLog + "echo '{\"mcl\": {\"field\": {\"beams\": 0}}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: MclOptions.field: LikelihoodFieldOptions.beams: expected ≥ 1, got 0"},
      {"mcl_field_resolution_tiny", kShortLog + "echo '{\"mcl\": {\"field\": {\"resolution\": 1e-6}}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: likelihood field: 1e+14 cells exceed the limit 25000000 (field.resolution 1e-06"},
      {"mcl_field_margin_huge", kShortLog + "echo '{\"mcl\": {\"field\": {\"margin\": 1e6}}}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: likelihood field: 1.60001e+15 cells exceed the limit 25000000 (field.resolution"},
      {"grid_field_margin_huge", kShortLog + "echo '{\"grid_markov\": {\"field\": {\"margin\": 1e4}}}' > '{d}/o.json'",
       "localize --method grid_markov --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json", 2,
       "o.json: likelihood field: 1.60129e+11 cells exceed the limit 25000000 (field.resolution"},
      {"map_far_away_segments",
       kShortLog + "echo '{\"name\": \"e\", \"segments\": [[0, 0, 1e6, 0], [0, 0, 0, 1e6]]}' > '{d}/m.json'",
       "localize --map {d}/m.json --log {d}/l.clf", 2,
       "likelihood field: 4.00002e+14 cells exceed the limit 25000000 (field.resolution 0.05 m,"},
      // 17. Bad files, flags and verbs: each names the file, line, key or flag and what was expected.
      {"diagnose_window_zero", kShortLog, "diagnose {d}/l.clf --window 0", 2,
       "--window 0: expected a length in (0, 3600] s"},
      {"diagnose_window_past", kShortLog, "diagnose {d}/l.clf --window 3601", 2,
       "--window 3601: expected a length in (0, 3600] s"},
      {"diagnose_false_alarm_half", kShortLog, "diagnose {d}/l.clf --false-alarm 0.5", 2,
       "--false-alarm 0.5: expected a level in [1e-12, 0.5)"},
      {"diagnose_histogram_with_scenario", "", "diagnose {src}/examples/table_3_1_histogram.json --scenario {d}/t.json",
       2, "--scenario needs a log: a histogram of residuals has no motion to replay"},
      {"diagnose_empty_file", ": > '{d}/e.clf'", "diagnose {d}/e.clf", 2,
       "e.clf: empty file: expected at least one line of data"},
      {"diagnose_params_only", kShortLog + "grep PARAM '{d}/l.clf' > '{d}/p.clf'", "diagnose {d}/p.clf", 2,
       "p.clf: no odometry: expected ENCODER records, at least two ODOM records or FLASER"},
      {"diagnose_truncated_encoder_line", kShortLog + "echo 'ENCODER 5' >> '{d}/l.clf'", "diagnose {d}/l.clf", 2,
       "l.clf:95: ENCODER: expected 5 fields after the tag, found 1"},
      {"diagnose_encoder_word", kShortLog + "echo 'ENCODER five 5 1.0 h 1.0' >> '{d}/l.clf'", "diagnose {d}/l.clf", 2,
       "l.clf:95: ENCODER: left_ticks: expected an integer, found 'five'"},
      {"diagnose_truepos_nan", kShortLog + "echo 'TRUEPOS nan 0 0 0 0 0 9 h 9' >> '{d}/l.clf'", "diagnose {d}/l.clf", 2,
       "l.clf:95: TRUEPOS: true_x: expected a finite number, found 'nan'"},
      {"diagnose_flaser_count_lies", kShortLog + "echo 'FLASER 5 1 1 0 0 0 0 0 0 9 h 9' >> '{d}/l.clf'",
       "diagnose {d}/l.clf", 2,
       "l.clf:95: FLASER: expected 1 + n + 9 = 15 fields after the tag for n = 5 beams, found 12"},
      {"diagnose_binary_garbage", "head -c 4096 /dev/urandom > '{d}/g.clf'", "diagnose {d}/g.clf", 2,
       "g.clf:1: expected a record type such as ODOM, FLASER, TRUEPOS, ENCODER, COMPASS or PARAM,"},
      {"diagnose_time_going_backwards", kShortLog + "echo 'ENCODER 999 999 0.001 h 0.001' >> '{d}/l.clf'",
       "diagnose {d}/l.clf", 2,
       "l.clf:95: ENCODER: timestamp 0.001 goes back in time: the previous ENCODER record (line"},
      {"diagnose_relations_garbage", kShortLog + "echo 'hello world' > '{d}/r.relations'",
       "diagnose {d}/l.clf --relations {d}/r.relations", 2, "r.relations:1: expected 8 fields, found 2"},
      {"diagnose_relations_missing", kShortLog, "diagnose {d}/l.clf --relations {d}/none.relations", 2,
       "none.relations: cannot open the input file: no such file"},
      {"diagnose_log_missing", "", "diagnose {d}/none.clf", 2,
       "none.clf: no such file or folder (accepted: a CARMEN log (.clf, .log or .carmen,"},
      {"diagnose_mrclam_folder_missing", "mkdir '{d}/mr'", "diagnose '{d}/mr#robot1'", 2,
       "mr: not an MRCLAM dataset folder: no RobotN_Odometry.dat (accepted: a CARMEN log (.clf,"},
      {"histogram_negative_count",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4,5],\"counts\":[10,-20,30,20,10]}' > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: counts[1]: expected a whole number of samples ≥ 0, found -20"},
      {"histogram_unknown_unit",
       "echo '{\"residual\":\"r\",\"unit\":\"furlong\",\"edges\":[0,1,2,3,4,5],\"counts\":[10,20,30,20,10]}' > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: unit 'furlong': expected one of deg, rad, mm, m"},
      {"histogram_edges_decreasing",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,2,5],\"counts\":[10,20,30,20,10]}' > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: edges[4]: edges must increase"},
      {"histogram_edges_count_mismatch",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4],\"counts\":[10,20,30,20,10]}' > '{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: 5 edges for 5 counts: expected one edge more than counts"},
      {"histogram_four_bins",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4],\"counts\":[10,20,30,20]}' > '{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: too short: at least 5 bins needed"},
      {"histogram_29_samples",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4,5],\"counts\":[5,6,7,6,5]}' > '{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: too few samples: 29 counted, at least 30 needed"},
      {"histogram_edge_1e10",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4,1e10],\"counts\":[10,20,30,20,10]}' > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: edges[5]: 10000000000 is not a finite edge within ±1e9 deg"},
      {"histogram_missing_counts",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4,5]}' > '{d}/h.json'", "diagnose {d}/h.json", 2,
       "h.json: counts: missing field"},
      {"histogram_counts_is_a_string",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2,3,4,5],\"counts\":\"many\"}' > '{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: 'edges' and 'counts' must be arrays of numbers"},
      {"histogram_top_level_array", "echo '[1, 2, 3]' > '{d}/h.json'", "diagnose {d}/h.json", 2,
       "h.json: top level: expected an object, found array"},
      {"histogram_truncated_json", "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,2' > '{d}/h.json'",
       "diagnose {d}/h.json", 2,
       "h.json:2: invalid JSON: [json.exception.parse_error.101] parse error at line 2, column 1:"},
      {"histogram_string_edge",
       "echo '{\"residual\":\"r\",\"unit\":\"deg\",\"edges\":[0,1,\"2\",3,4,5],\"counts\":[10,20,30,20,10]}' > "
       "'{d}/h.json'",
       "diagnose {d}/h.json", 2, "h.json: edges[2]: expected a number"},
      {"simulate_unknown_preset", "", "simulate hallway -o {d}/x.clf", 2,
       "unknown simulator preset 'hallway' (known: ideal, corridor, umbmark_trilobot,"},
      {"simulate_unknown_key", "echo '{\"preset\": \"corridor\", \"lazer\": {}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: lazer: unknown key (expected one of: preset, name, description, world, start,"},
      {"simulate_speed_zero", "echo '{\"preset\": \"corridor\", \"drive\": {\"speed\": 0}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: scenario: drive.speed must be > 0"},
      {"simulate_step_negative", "echo '{\"preset\": \"corridor\", \"physics\": {\"step\": -0.001}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: scenario: physics.step must be > 0"},
      {"simulate_laser_beams_one",
       "echo '{\"preset\": \"corridor\", \"laser\": {\"enabled\": true, \"beams\": 1}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 0, "wrote"},
      {"simulate_laser_beams_zero",
       "echo '{\"preset\": \"corridor\", \"laser\": {\"enabled\": true, \"beams\": 0}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: scenario: laser.beams must be >= 1"},
      {"simulate_waypoints_empty",
       "echo '{\"preset\": \"corridor\", \"motion\": {\"kind\": \"waypoints\", \"waypoints\": []}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2, "s.json: scenario: motion.waypoints must be non-empty"},
      {"simulate_unknown_motion_kind",
       "echo '{\"preset\": \"corridor\", \"motion\": {\"kind\": \"teleport\"}}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf", 2,
       "s.json: motion.kind: unknown value 'teleport' (expected one of: straight, umbmark,"},
      {"simulate_output_in_missing_folder", "", "simulate corridor -o {d}/no/such/x.clf", 2,
       "no/such/x.clf: cannot open for writing (a temporary file beside it): No such file or"},
      {"simulate_output_is_a_folder", "mkdir '{d}/x.clf'", "simulate corridor -o {d}/x.clf", 2,
       "x.clf: is a folder: expected the path of a file to write"},
      {"run_unknown_experiment", "", "run odometry/nothing --out {d}/out", 2,
       "no experiment named \"odometry/nothing\" (see `locbench list`)"},
      {"run_set_unknown_key", "", "run odometry/sim_corridor --set nonsense=1 --out {d}/out", 2,
       "--set nonsense=1: no chosen experiment has an option \"nonsense\""},
      {"run_set_runs_word", "", "run odometry/sim_corridor --set runs=abc --out {d}/out", 2,
       "configuration: option runs expects a number, got a string"},
      {"run_set_without_equals", "", "run odometry/sim_corridor --set runs --out {d}/out", 2,
       "--set runs: expected KEY.PATH=VALUE"},
      {"run_data_missing_folder", "", "run odometry/real_logs --data {d}/nowhere --out {d}/out", 2,
       "nowhere: --data: no such folder (the datasets' folder, see `locbench list`)"},
      {"run_config_unknown_experiment", "echo '{\"odometry/nothing\": {}}' > '{d}/c.json'",
       "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2,
       "c.json: configuration for unknown experiment \"odometry/nothing\""},
      {"run_config_top_level_array", "echo '[]' > '{d}/c.json'",
       "run odometry/sim_corridor --config {d}/c.json --out {d}/out", 2,
       "c.json: expected a JSON object keyed by experiment name"},
      {"gate_baseline_missing",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1",
       "gate {d}/r.json --baseline {d}/none.json", 2, "none.json: no such file or folder"},
      {"gate_current_missing",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1",
       "gate {d}/none.json --baseline {d}/r.json", 2, "none.json: no such file or folder"},
      {"gate_rules_unknown_key",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1; "
       "echo '{\"nonsense\": 1}' > '{d}/rules.json'",
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json", 2,
       "rules.json: rules.nonsense: unknown key (expected one of: comment, fail_on_missing,"},
      {"gate_empty_current_folder",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1; "
       "mkdir '{d}/c'",
       "gate {d}/c --baseline {d}/r.json", 2, "c: folder holds no .json report"},
      {"gate_report_is_a_histogram", "",
       "gate {src}/examples/table_3_1_histogram.json --baseline {src}/examples/table_3_1_histogram.json", 2,
       "table_3_1_histogram.json: expected a locbench report"},
      {"report_empty_folder", "mkdir '{d}/o'", "report {d}/o -o {d}/p.html", 2, "o: folder holds no locbench reports"},
      {"report_missing_folder", "", "report {d}/none -o {d}/p.html", 2, "reports: Path does not exist:"},
      {"merge_no_shards", "mkdir '{d}/s'", "merge {d}/s -o {d}/o", 2, "s: folder holds no *.shard-K-of-N.json files"},
      {"merge_shard_garbage", "mkdir '{d}/s'; echo 'garbage' > '{d}/s/x.shard-1-of-1.json'", "merge {d}/s -o {d}/o", 2,
       "s/x.shard-1-of-1.json:1: invalid JSON: [json.exception.parse_error.101] parse error at"},
      {"merge_missing_folder", "", "merge {d}/none -o {d}/o", 2, "shards: Path does not exist:"},
      {"calibrate_unknown_method", "", "calibrate wizardry {src}/examples/umbmark_trilobot.json", 2,
       "calibrate: METHOD must be umbmark-classic, umbmark-improved or ml, not \"wizardry\""},
      {"calibrate_umbmark_empty_object", "echo '{}' > '{d}/u.json'", "calibrate umbmark-classic {d}/u.json", 2,
       "u.json: side_length_m: missing field"},
      {"calibrate_umbmark_improved_empty_object", "echo '{}' > '{d}/u.json'", "calibrate umbmark-improved {d}/u.json",
       2, "u.json: side_length_m: missing field"},
      {"calibrate_ml_empty_file", ": > '{d}/t.tuple'", "calibrate ml {d}/t.tuple", 2,
       "t.tuple: empty file: expected at least one line of data"},
      {"calibrate_ml_tuple_garbage", "echo 'not a tuple' > '{d}/t.tuple'", "calibrate ml {d}/t.tuple", 2,
       "t.tuple:1: expected JSON: parse error at line 1, column 2: syntax error while parsing"},
      {"calibrate_ml_tuple_nan",
       "for i in 1 2 3 4 5 6 7 8 9 10; do echo '{ \"T\": 1, \"phi_l\": NaN, \"phi_r\": 0.1, \"sm\": [0.1, 0, 0] }'; "
       "done > '{d}/t.tuple'",
       "calibrate ml {d}/t.tuple", 2,
       "t.tuple:1: expected JSON: parse error at line 1, column 20: syntax error while parsing"},
      {"calibrate_ml_tuple_negative_interval",
       "for i in 1 2 3 4 5 6 7 8 9 10; do echo '{ \"T\": -1, \"phi_l\": 0.1, \"phi_r\": 0.1, \"sm\": [0.1, 0, 0] }'; "
       "done > '{d}/t.tuple'",
       "calibrate ml {d}/t.tuple", 2, "t.tuple:1: \"T\": expected an interval > 0 s"},
      {"calibrate_ml_unknown_dataset", "", "calibrate ml nothing_like_this", 2,
       "nothing_like_this: no such file or folder (accepted: a CARMEN log"},
      {"list_extra_argument", "", "list extra more", 2, "The following argument was not expected: more"},
      {"list_log_missing", "", "list extra", 2, "extra: no such file or folder (accepted: a CARMEN log"},
      {"no_arguments", "", "", 2, "A subcommand is required"},
      // 18. Outputs onto inputs (data loss) and estimates judged before they are reported: UMBmark
      // input that is not geometry, collinear tuples, a robot that never moves, truth x1e300 and a
      // 1e9-tick glitch (these three got a verdict before).
      {"diagnose_scenario_onto_relations", kShortLog + "echo '# none' > '{d}/r.relations'",
       "diagnose {d}/l.clf --relations {d}/r.relations --scenario {d}/r.relations", 2,
       "r.relations: --scenario would overwrite the input"},
      {"gate_json_onto_baseline",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1; "
       "cp '{d}/r.json' '{d}/b.json'",
       "gate {d}/r.json --baseline {d}/b.json --json {d}/b.json", 2, "b.json: --json would overwrite the input"},
      {"gate_markdown_onto_rules",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1; "
       "echo '{\"accuracy\": []}' > '{d}/rules.json'",
       "gate {d}/r.json --baseline {d}/r.json --rules {d}/rules.json --markdown {d}/rules.json", 2,
       "rules.json: --markdown would overwrite the input"},
      {"gate_json_and_markdown_same_file",
       "{exe} calibrate umbmark-classic '{src}/examples/umbmark_trilobot.json' --report '{d}/r.json' >/dev/null 2>&1",
       "gate {d}/r.json --baseline {d}/r.json --json {d}/v.out --markdown {d}/v.out", 2,
       "v.out: --json and --markdown name the same file: give each output its own path"},
      {"localize_report_onto_options", kShortLog + "echo '{}' > '{d}/o.json'",
       "localize --map {src}/examples/room_map.json --log {d}/l.clf --options {d}/o.json --report {d}/o.json", 2,
       "o.json: --report would overwrite the input"},
      {"match_report_onto_map", kShortLog + "cp '{src}/examples/room_map.json' '{d}/m.json'",
       "match --map {d}/m.json --log {d}/l.clf --report {d}/m.json", 2, "m.json: --report would overwrite the input"},
      {"match_report_and_tum_same_file", kShortLog,
       "match --map {src}/examples/room_map.json --log {d}/l.clf --report {d}/x.out --tum {d}/x.out", 2,
       "x.out: --tum and --report name the same file: give each output its own path"},
      {"localize_report_onto_map_through_dot_dot",
       kShortLog + "mkdir '{d}/a'; cp '{src}/examples/room_map.json' '{d}/m.json'",
       "localize --map {d}/m.json --log {d}/l.clf --report {d}/a/../m.json", 2,
       "a/../m.json: --report would overwrite the input"},
      {"calibrate_ml_report_onto_tuples",
       "for i in 1 2 3 4 5 6 7 8 9 10; do echo '{ \"T\": 1, \"phi_l\": 0.1, \"phi_r\": 0.1, \"sm\": [0.1, 0, 0] }'; "
       "done > '{d}/t.tuple'",
       "calibrate ml {d}/t.tuple --report {d}/t.tuple", 2, "t.tuple: --report would overwrite the input"},
      {"simulate_truth_tum_onto_scenario", "echo '{\"preset\": \"corridor\"}' > '{d}/s.json'",
       "simulate {d}/s.json -o {d}/x.clf --truth-tum {d}/s.json", 2, "s.json: --truth-tum would overwrite the input"},
      {"umbmark_negative_side",
       "sed 's/\"side_length_m\": 1.6/\"side_length_m\": -1.6/' '{src}/examples/umbmark_trilobot.json' > '{d}/u.json'",
       "calibrate umbmark-classic {d}/u.json", 2, "u.json: side_length_m: must be > 0, got -1.6"},
      {"umbmark_kilometre_errors",
       "sed -E 's/\"x_error_m\": (-?)0/\"x_error_m\": \\19000/' '{src}/examples/umbmark_trilobot.json' > '{d}/u.json'",
       "calibrate umbmark-improved {d}/u.json", 2,
       "u.json: runs[0].x_error_m: -9000.577 is longer than the side (1.6 m): looks like"},
      {"umbmark_only_cw_runs",
       "grep -v ccw '{src}/examples/umbmark_trilobot.json' | sed 's/0.678 },/0.678 }/' > '{d}/u.json'",
       "calibrate umbmark-classic {d}/u.json", 2,
       "u.json: runs: has 5 clockwise and 0 counter-clockwise runs: UMBmark needs both directions"},
      {"umbmark_unknown_direction",
       "sed 's/\"direction\": \"ccw\"/\"direction\": \"widdershins\"/' '{src}/examples/umbmark_trilobot.json' > "
       "'{d}/u.json'",
       "calibrate umbmark-classic {d}/u.json", 2,
       "u.json: runs[5].direction: expected \"cw\" or \"ccw\", found string \"widdershins\""},
      {"umbmark_zero_leg_ticks",
       "sed 's/\"left\": 127, \"right\": 127/\"left\": 0, \"right\": 0/' '{src}/examples/umbmark_trilobot.json' > "
       "'{d}/u.json'",
       "calibrate umbmark-improved {d}/u.json", 2,
       "u.json: leg_ticks.left: must be > 0 (counts of one straight leg), got 0"},
      {"umbmark_tape_scale_zero",
       "sed 's/\"tape_measure_scale\": 1.0/\"tape_measure_scale\": 0/' '{src}/examples/umbmark_trilobot.json' > "
       "'{d}/u.json'",
       "calibrate umbmark-classic {d}/u.json", 2, "u.json: tape_measure_scale: must be > 0, got 0"},
      {"umbmark_counts_per_rev_zero",
       "sed 's/\"counts_per_rev\": 22/\"counts_per_rev\": 0/' '{src}/examples/umbmark_trilobot.json' > '{d}/u.json'",
       "calibrate umbmark-classic {d}/u.json", 2, "u.json: nominal.counts_per_rev: must be > 0, got 0"},
      {"calibrate_ml_tuples_collinear",
       "for i in 1 2 3 4 5 6 7 8 9 10 11 12; do echo '{ \"T\": 1, \"phi_l\": 0.5, \"phi_r\": 0.5, \"sm\": [0.04, 0, 0] "
       "}'; done > '{d}/t.tuple'",
       "calibrate ml {d}/t.tuple", 0, "the data do not determine b, sensor_x, sensor_y"},
      {"calibrate_ml_tuples_sm_huge",
       "for i in 1 2 3 4 5 6 7 8 9 10 11 12; do echo \"{ \\\"T\\\": 1, \\\"phi_l\\\": 0.$i, \\\"phi_r\\\": -0.$i, "
       "\\\"sm\\\": [1e12, 0, 0.$i] }\"; done > '{d}/t.tuple'",
       "calibrate ml {d}/t.tuple", 2,
       "t.tuple: 0 samples give 0 measurements for 6 free parameters after outlier rejection:"},
      {"diagnose_robot_standing_still",
       "{ echo 'PARAM robot_meters_per_tick_left 0.0126 0 h 0'; echo 'PARAM robot_meters_per_tick_right 0.0127 0 h 0'; "
       "echo 'PARAM robot_wheelbase 0.198 0 h 0'; for i in $(seq 0 600); do echo \"ENCODER 0 0 $i.0 h $i.0\"; echo "
       "\"TRUEPOS 1 1 0 1 1 0 $i.0 h $i.0\"; done; } > '{d}/still.clf'",
       "diagnose {d}/still.clf", 2,
       "still.clf: the odometry shows no motion in any of its 600 windows (0 m, 0 rad): a robot"},
      {"diagnose_truth_times_1e300",
       "{exe} simulate corridor --seed 7 -o '{d}/c.clf' >/dev/null 2>&1; awk '$1==\"TRUEPOS\"{$2=$2*1e300;$3=$3*1e300} "
       "{print}' '{d}/c.clf' > '{d}/b.clf'",
       "diagnose {d}/b.clf", 2, "b.clf: TRUEPOS travels 1.00073e+301 m over the windows in which the odometry travels"},
      {"diagnose_one_encoder_glitch",
       "{exe} simulate corridor --seed 7 -o '{d}/c.clf' >/dev/null 2>&1; awk '$1==\"ENCODER\" && ++n==80 "
       "{$2=$2+1000000000} {print}' '{d}/c.clf' > '{d}/g.clf'",
       "diagnose {d}/g.clf", 2,
       "g.clf: ENCODER at t = 19.784: a wheel travels 1.26378e+07 m in 0.317 s since the previous"},
      // 19. ROS bags (datasets/io/bag_log.h): truncated, a topic missing or of the wrong type, a bad
      // topic choice, storage not read; every verb through the same opener.
      {"bag_truncated", kShortBags + "head -c 3000 '{d}/l.bag' > '{d}/t.bag'", "diagnose {d}/t.bag", 2,
       "t.bag: not a readable ROS 1 bag: byte"},
      {"bag_truncated_list", kShortBags + "head -c 3000 '{d}/l.bag' > '{d}/t.bag'", "list {d}/t.bag", 2,
       "t.bag: not a readable ROS 1 bag: byte"},
      {"bag_truncated_real_log_experiment", kShortBags + "head -c 3000 '{d}/l.bag' > '{d}/t.bag'",
       "run diagnosis/real_logs --log {d}/t.bag -o {d}/o", 2, "t.bag: not a readable ROS 1 bag"},
      {"bag_empty", "touch '{d}/e.bag'", "diagnose {d}/e.bag", 2,
       "e.bag: not a readable ROS 1 bag: byte 0: no \"#ROSBAG V2.0\" line"},
      {"bag_missing_topic", kShortBags, "diagnose '{d}/l.bag#odom=/wheel_odom'", 2,
       "l.bag: #odom=/wheel_odom: no such topic in the bag (topics: /ground_truth"},
      {"bag_wrong_message_type", kShortBags, "diagnose '{d}/l.bag#odom=/scan'", 2,
       "l.bag: topic /scan (#odom=) is a sensor_msgs/LaserScan, expected nav_msgs/Odometry or "
       "geometry_msgs/TwistStamped or "
       "geometry_msgs/Twist for the odometry"},
      {"bag_unknown_topic_key", kShortBags, "diagnose '{d}/l.bag#odometry=/odom'", 2,
       "'odometry=/odom' after '#': unknown key \"odometry\""},
      {"bag_no_odometry", kShortBags, "calibrate ml '{d}/l2#odom=none'", 2, "l2: no odometry topic"},
      {"ros2_bag_truncated_database", kShortBags + "truncate -s 5000 '{d}/l2/l2_0.db3'", "diagnose {d}/l2", 2,
       "l2_0.db3: reading the bag: database disk image is malformed"},
      {"ros2_bag_wrong_message_type", kShortBags, "list '{d}/l2#truth=/scan'", 2,
       "l2: topic /scan (#truth=) is a sensor_msgs/LaserScan, expected geometry_msgs/PoseStamped or"},
      {"ros2_bag_mcap_empty_file", "mkdir '{d}/m' && touch '{d}/m/metadata.yaml' '{d}/m/m_0.mcap'", "diagnose {d}/m", 2,
       "m_0.mcap: opening:"},
      {"mcap_truncated", kShortBags + "truncate -s 3000 '{d}/l.mcap'", "diagnose {d}/l.mcap", 2,
       "l.mcap: does not end with MCAP's closing magic bytes: cut short"},
      // 2 GB sparse files (no disk used): refused from their first or last bytes, at once.
      {"mcap_2gb_sparse_tail", kShortBags + "truncate -s 2G '{d}/l.mcap'", "diagnose {d}/l.mcap", 2,
       "l.mcap: does not end with MCAP's closing magic bytes"},
      {"bag_2gb_sparse_tail", kShortBags + "truncate -s 2G '{d}/l.bag'", "diagnose {d}/l.bag", 2,
       "l.bag: not a readable ROS 1 bag: byte"},
      {"bag_2gb_sparse", "truncate -s 2G '{d}/z.bag'", "diagnose {d}/z.bag", 2,
       "z.bag: not a readable ROS 1 bag: byte 0: no \"#ROSBAG V2.0\" line at the start"},
      {"db3_2gb_sparse", "truncate -s 2G '{d}/z.db3'", "diagnose {d}/z.db3", 2,
       "z.db3: reading the bag: file is not a database"},
      {"mcap_2gb_sparse", "truncate -s 2G '{d}/z.mcap'", "diagnose {d}/z.mcap", 2, "z.mcap: opening:"},
      {"mcap_wrong_message_type", kShortBags, "list '{d}/l.mcap#truth=/scan'", 2,
       "l.mcap: topic /scan (#truth=) is a sensor_msgs/LaserScan, expected geometry_msgs/PoseStamped or"},
      {"mcap_file_compressed", "mkdir '{d}/z' && touch '{d}/z/metadata.yaml' '{d}/z/z_0.mcap.zstd'", "diagnose {d}/z",
       2, "z_0.mcap.zstd: a ROS 2 bag compressed file by file: not read"},
  };
  return all;
}

class Hostile : public ::testing::TestWithParam<HostileCase> {};

std::string substitute(std::string s, const std::string& key, const std::string& value) {
  for (std::size_t p = s.find(key); p != std::string::npos; p = s.find(key, p + value.size()))
    s.replace(p, key.size(), value);
  return s;
}

TEST_P(Hostile, ExitsWithTheExpectedCodeAndMessage) {
  const HostileCase& c = GetParam();
  testing::ScratchDir dir;
  const std::string src = std::getenv("LOCBENCH_SOURCE_DIR") ? std::getenv("LOCBENCH_SOURCE_DIR") : ".";
  const auto fill = [&](std::string s) {
    s = substitute(s, "{exe}", LOCBENCH_EXE);
    s = substitute(s, "{src}", src);
    return substitute(s, "{d}", dir.path().string());
  };
  if (!c.setup.empty()) {
    const testing::Outcome setup = testing::run_shell("set -e\n" + fill(c.setup));
    ASSERT_EQ(setup.exit_code, 0) << "setup failed: " << setup.output;
  }
  const std::string command = fill(c.prefix) + " timeout 60 '" + std::string(LOCBENCH_EXE) + "' " + fill(c.args);
  const testing::Outcome o = testing::run_shell(command);
  EXPECT_NE(o.exit_code, 124) << "hung (over 60 s): " << o.output;
  EXPECT_NE(o.exit_code, 3) << "internal error: " << o.output;
  EXPECT_EQ(o.exit_code, c.exit_code) << o.output;
  EXPECT_NE(o.output.find(c.message), std::string::npos) << "expected \"" << c.message << "\" in:\n" << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
}

// gtest prints a failing case by its name, not its bytes.
void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.name; }

INSTANTIATE_TEST_SUITE_P(Cases, Hostile, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<HostileCase>& p) { return p.param.name; });

}  // namespace
}  // namespace locbench
