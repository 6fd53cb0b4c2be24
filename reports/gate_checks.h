#pragma once
// What a gate checks before it compares: that each series is a number that could have been
// measured, that a skipped result is backed by what the reports say, and that the current
// reports come from one run. Every rule here fails the gate (exit 1); README, "Hostile input",
// lists them.
#include <string>

#include "reports/gate_input.h"

namespace locbench::reports {

// True for a quantity that cannot be negative: a Google Benchmark time, or a report result whose
// unit is a length (m, cm, mm), an angle (rad, deg) or a time (s, ms, us, ns), whose `better` is
// "lower", and whose name (variant) is a time unit's or says it is an error ("error", "rmse",
// "rms", "rpe", "ape", "sigma"), unless it is a difference ("minus", "difference", "change").
bool is_magnitude(const GateSeries& s);

// Empty when the series could have been measured; else why not: a non-finite number; `values`
// that contradict n, mean, min or max (recomputed, relative tolerance 1e-9 of the largest
// |value|); a negative magnitude; a benchmark time ≤ 0.
std::string implausible(const GateSeries& s);

// True for a dataset read from a file (a skippable one): not "simulated", not transcribed.
bool is_recorded_data(const std::string& dataset_path);

// Empty when the current run's skip of the baseline series `s` is backed by provenance: the
// current report of s.experiment has a "skipped" case for s.dataset whose reason says the data
// were not found, lists no such dataset and has no result of it, and the baseline's report
// read s.dataset from a file. Else why the skip does not count.
std::string unbacked_skip(const GateSeries& s, const GateInput& baseline, const GateInput& current);

// True when `current` recorded a skip of s.dataset in s.experiment (backed or not).
bool recorded_skip(const GateSeries& s, const GateInput& current);

// Empty when every report of `in` carries the same run id (reports without one count as the id
// ""); else which files differ.
std::string mixed_run_ids(const GateInput& in);

}  // namespace locbench::reports
