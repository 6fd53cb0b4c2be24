#pragma once
#include <limits>
#include <vector>

#include "reports/report.h"

namespace locbench::testing {

// A small, fully populated report for tests.
inline reports::Report sample_report() {
  reports::Report r;
  r.provenance = {"0.1.0",
                  "abc123",
                  "GCC 12.2.0",
                  "-O2",
                  "Release",
                  "host",
                  "2026-11-21T12:00:00Z",
                  "locbench run smoke",
                  std::nullopt,
                  std::nullopt,
                  ""};
  r.body.experiment = "odometry/sim_corridor";
  r.body.description = "dead reckoning on a simulated corridor";
  r.body.seeds = {1, 2, 3};
  r.body.datasets = {{"sim/corridor", "simulated", "crc32:0123abcd", 1200, 40.0}};
  r.body.configuration = {{"runs", 3}, {"scenario", "corridor"}};
  const std::vector<double> v{0.10, 0.12, 0.08};
  r.body.results.push_back(
      reports::make_metric("odometry_nominal", "sim_corridor", "final_position_error", "m", "monte_carlo_runs", v));
  r.body.published.push_back({"thesis Table 3.2",
                              "final error",
                              "mm",
                              {{"run 1", 580.0, 512.3}, {"run 2", 551.0, std::nullopt}},
                              "differs because…"});
  r.body.cases.push_back({"odometry/aces", "skipped", "dataset not found"});
  r.body.results.push_back(reports::make_estimate("umbmark_improved", "sim_trilobot", "E_o", "", 1.0,
                                                  std::numeric_limits<double>::infinity(), 10));
  r.body.results.back().note = "only E_o/E_b is determined by the square";
  r.body.notes.push_back("a finding in plain words");
  return r;
}

}  // namespace locbench::testing
