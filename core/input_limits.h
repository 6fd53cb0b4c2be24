#pragma once
// Input limits: every input size that sets memory or time is checked against one of these
// before work starts, and a value beyond it is an InputError naming the key and the limit
// (exit 2). The same table is printed by `locbench --help` and listed in the README, so a user
// sees the limits before hitting them. Each limit is far above any real input the suite knows
// (noted beside it) and low enough that the work it allows stays under ~10 s and ~1 GB.
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "core/errors.h"

namespace locbench::limits {

struct Limit {
  std::string_view key;  // where it applies, as a user names it
  double max;            // inclusive
  std::string_view why;  // what it bounds
};

// Residual histograms (`diagnose H.json`): bins, bins holding samples and total count (the
// held-out split draws one coin per sample). Table 3.1 has 10 bins and 809 samples. Measured at
// -O1: 10,000 bins with 500 filled, spread out, take 5 s; 100,000 bins with 1,000
// filled took 25 s, 1,000 filled bins with random counts 10 s.
inline constexpr Limit kHistogramBins{"histogram bins (len(counts))", 10'000, "time of the fits"};
inline constexpr Limit kHistogramFilledBins{"histogram bins holding samples (counts > 0)", 500, "time of the fits"};
inline constexpr Limit kHistogramTotalCount{"histogram total count (sum of counts)", 1e7, "time of the held-out split"};
// Simulation (`simulate`, scenario JSON). The presets run minutes of robot time with 181 beams.
inline constexpr Limit kSimLaserBeams{"laser.beams", 10'000, "memory per scan (Hokuyo UTM: 1,081)"};
inline constexpr Limit kSimCoordinate{"|coordinates| of start, waypoints, world segments [m]", 1e4, "path length"};
inline constexpr Limit kSimDistance{"motion.distance, motion.side [m]", 1e4, "path length"};
inline constexpr Limit kSimRuns{"motion.runs", 1'000, "UMBmark runs per direction"};
inline constexpr Limit kSimDuration{"estimated simulated time [s]", 1e4, "physics steps and records"};
inline constexpr Limit kSimPhysicsSteps{"estimated simulated time / physics.step", 2e7, "time of the simulation"};
// At 10^7 records a sensor and 2·10^7 ranges a simulation took 62 s and 5.6 GB (a 3.6 GB log no
// reader accepts); 10^6 and 2·10^6 keep it to seconds and under 1 GB.
inline constexpr Limit kSimRecords{"estimated records of one sensor (time x rate)", 1e6, "memory of the log"};
inline constexpr Limit kSimLaserValues{"estimated laser ranges (scans x beams)", 2e6,
                                       "memory of the log (8 bytes each)"};
// Scan matching (`match`, `localize`): beams of one scan (the clustering baselines are
// quadratic in them). SICK LMS: 181 or 361.
inline constexpr Limit kBeamsPerScan{"beams of one laser scan", 10'000, "time of the matchers"};
// All ranges of a log (`match`, `localize`): RWHT costs ~3 µs a range; the agglomerative
// matcher is quadratic in a scan's beams (~27 ns per beam², 203 scans of 1,000 beams: 5.4 s).
inline constexpr Limit kLaserRangesPerLog{"laser ranges of one log (sum of beams over scans)", 2e6,
                                          "time of the matchers"};
inline constexpr Limit kAgglomerativeWork{"agglomerative matcher: sum over scans of beams^2", 2e8,
                                          "time of the clustering"};
// `diagnose LOG` costs ~0.2 ms per odometry record (56,000 ENCODER records with TRUEPOS and
// COMPASS: 12 s). Catalog datasets, named by name, are exempt (their times are measured in the
// README: 3–32 s); `diagnose --max-records N` raises the limit for one log.
inline constexpr Limit kDiagnoseOdometryRecords{"diagnose: odometry records of a log file (ENCODER, ODOM)", 30'000,
                                                "time of the fits (--max-records raises it)"};
// Monte-Carlo runs (`run --runs`, "runs" options): odometry/sim_corridor takes ~7 ms a run
// (100,000 runs: over 120 s; 1,000: 6.8 s); the suite's largest is `--runs 1000`.
inline constexpr Limit kMonteCarloRuns{"--runs / runs", 1'000, "time and memory of the runs"};
// Landmark maps and observations (`--landmark-map`, `--landmark-observations`, MRCLAM
// Landmark_Groundtruth.dat). MRCLAM dataset 6: 15 landmarks; robot 3 has 5,627 observations.
// noise/landmark_logs filters every observation once per setting of its grid: 10^6 observations
// of a 100,000-landmark map ran over 300 s in 1.4 GB; 20,000 of a 10,000-landmark map 9.2 s. The
// observation limit is set by real logs, not by 10 s: MRCLAM robots record ~6 observations a
// second, so 200,000 is ~9 hours of one robot (Dataset 6's 15-minute files hold up to 5,627); the
// filters' time grows linearly with them.
inline constexpr Limit kLandmarkMapSize{"landmarks of a landmark map", 10'000, "time of data association"};
inline constexpr Limit kLandmarkObservations{"landmark observations of one file", 200'000,
                                             "time of the landmark filters (linear in them)"};

// Every input file (core/input_file.h): its bytes, decompressed ones for gzip (the largest
// catalog log, Intel's CARMEN file, is 18 MB decompressed; 128 MiB of ODOM lines parse in ~2.5 s
// into ~400 MB), and for JSON its bytes and nesting (reports are under 1 MB; a 32 MiB array of
// numbers parses in ~1 s into ~0.5 GB; copies and destruction recurse once per level).
inline constexpr Limit kInputFileBytes{"bytes of one input file (decompressed, for gzip)", 134'217'728,
                                       "memory and time of reading it (128 MiB)"};
inline constexpr Limit kJsonFileBytes{"bytes of one JSON input", 33'554'432, "memory of the parsed document (32 MiB)"};
inline constexpr Limit kJsonDepth{"nesting depth of a JSON input (arrays and objects)", 512,
                                  "stack depth of the parser and of copies"};

// Global localization (`localize`, global/real_logs options): MCL's particle counts and grid
// Markov's cells (each cell a double, with a second grid for the prediction). The catalog
// experiments use 50,000 initial particles; grid Markov's default max_cells is the limit.
inline constexpr Limit kMclParticles{"mcl initial_particles, min_particles, max_particles", 1e6,
                                     "memory and time of each update"};
// The likelihood field of MCL and grid Markov: (map extent + 2 margin)² / resolution² cells, two
// floats each plus the distance transform. At 2.5·10^7 cells (1 cm on a 50 m map) it builds in
// 2.8 s into 400 MB; the old unstated cap, 4·10^8 cells, meant ~6 GB.
inline constexpr Limit kLikelihoodFieldCells{"likelihood field cells ((extent + 2 margin)^2 / resolution^2)", 2.5e7,
                                             "memory and time of the field"};
inline constexpr Limit kGridMarkovCells{"grid_markov max_cells", 1e7, "memory of the grid (8 bytes a cell, twice)"};
// The work of a whole `localize` run: each update weighs every particle (cell) with
// field.beams beams, plus a fixed cost a particle (KLD sampling and resampling, ~80 beams' worth:
// at +40, a tiny kld_bin with 1 beam reached the limit after 7.7 s) or a cell (the action update,
// ~10 beams). Updates are counted from the log's odometry and update_min_distance /
// update_min_angle before any work. MCL's particle count is known only as KLD sampling runs: the
// least it must do is checked first, the rest as it runs (cli/cmd_localize.cpp).
inline constexpr Limit kMclWork{"mcl: particles x (field.beams + 80), summed over the updates", 2e8,
                                "time of the filter (KLD sampling costs ~80 beams a particle)"};
// grid Markov: ~7 ns a cell and beam, plus ~70 ns a cell for the action update (10 beams' worth);
// 4.5·10^6 cells x 20 beams x 10 updates took 10.6 s at the old 10^9 product without the +10.
inline constexpr Limit kGridMarkovWork{"grid_markov: cells x (field.beams + 10) x updates", 8e8, "time of the filter"};

inline constexpr Limit kAll[] = {kInputFileBytes,
                                 kJsonFileBytes,
                                 kJsonDepth,
                                 kHistogramBins,
                                 kHistogramFilledBins,
                                 kHistogramTotalCount,
                                 kDiagnoseOdometryRecords,
                                 kSimLaserBeams,
                                 kSimCoordinate,
                                 kSimDistance,
                                 kSimRuns,
                                 kSimDuration,
                                 kSimPhysicsSteps,
                                 kSimRecords,
                                 kSimLaserValues,
                                 kBeamsPerScan,
                                 kLaserRangesPerLog,
                                 kAgglomerativeWork,
                                 kMonteCarloRuns,
                                 kLandmarkMapSize,
                                 kLandmarkObservations,
                                 kMclParticles,
                                 kMclWork,
                                 kLikelihoodFieldCells,
                                 kGridMarkovCells,
                                 kGridMarkovWork};

// "limit: 1e+04" style text for messages and --help.
inline std::string limit_text(double max) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", max);
  return buf;
}

// Throws InputError(file, 0, "<key>: <value> exceeds the limit <max> (<why>)") unless
// value ≤ limit (NaN fails too). `key` names the exact key in the input.
inline void check(double value, const Limit& limit, const std::string& file, const std::string& key) {
  if (value <= limit.max) return;
  char v[32];
  std::snprintf(v, sizeof v, "%.6g", value);
  throw InputError(file, 0,
                   key + ": " + v + " exceeds the limit " + limit_text(limit.max) + " (" + std::string(limit.why) +
                       "; see `locbench --help`, \"Input limits\")");
}

// The table for --help and the README.
inline std::string limits_help() {
  std::string s = "Input limits (checked before any work; exit 2 naming the key):\n";
  for (const Limit& l : kAll) {
    s += "  " + std::string(l.key) + " <= " + limit_text(l.max) + "  (" + std::string(l.why) + ")\n";
  }
  return s;
}

}  // namespace locbench::limits
