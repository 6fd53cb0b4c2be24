#pragma once
// How close a log's twins are to it: the nominal-model window residuals of the log against those
// of its nominal and its extended twin (twin_scenario.h), per component (x along, y left, θ),
// compared by the two-sample Kolmogorov–Smirnov distance D with its p-value
// (core/two_sample_ks.h). Windows are paired in time, so all three samples cover the
// same stretches of the log; each twin is simulated with `runs` seeds and pooled. The gain of
// the extended model is the reduction of D: ratio = D_extended / D_nominal (< 1 is closer).
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/two_sample_ks.h"
#include "pipelines/twin/twin_scenario.h"

namespace locbench::sim {

struct ComponentComparison {
  std::string window;     // "1s", "10s" or "relations"
  std::string component;  // "x", "y", "theta"
  KsResult nominal, extended;
  double ratio() const { return nominal.d > 0.0 ? extended.d / nominal.d : (extended.d > 0.0 ? INFINITY : 1.0); }
  std::vector<double> real, nominal_twin, extended_twin;  // the samples compared
};

// One comparison per window length in `windows_s` (a relations log: only the first, its
// relations being the windows) and component, in that order; `real` is the log `twin` was built
// from, whose windows of twin.residual_window_s are taken from the twin. Each twin is simulated `runs`
// times (seeds derived from `seed`) and read over every window set. Throws InputError when fewer
// than 5 windows are covered by the log's and the twins' references.
std::vector<ComponentComparison> compare_twins(const Log& real, const Twin& twin, const std::vector<double>& windows_s,
                                               int runs, std::uint64_t seed);

}  // namespace locbench::sim
