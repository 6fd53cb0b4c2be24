#pragma once
// Predictivity of a simulator: does a twin forecast how each method fares on the real
// log? For one metric, each cell is one method on one log: its real value and the values of
// seeded twin runs. The twin's 95% predictive interval is the 2.5–97.5% quantiles of its runs
// (type 7), its prediction their median. Across the cells of one metric (never pooled across
// metrics of different scales):
// - coverage: how many real values the predictive intervals contain;
// - Pearson r and Spearman ρ between the predictions and the real values (Kadian et al. 2020,
//   "Sim2Real predictivity": the sim-vs-real correlation);
// - MMRV, the mean maximum rank violation of the method ranking per log (Li et al. 2024, SIMPLER):
//   per log, RV(i, j) = |R_i − R_j| · [ (S_i < S_j) ≠ (R_i < R_j) ] for real R and predicted S,
//   MMRV_log = mean_i max_j RV(i, j), averaged over logs. SIMPLER's R are success rates in
//   [0, 1]; ours have units, so each |R_i − R_j| is divided by the log's mean |R| (a fraction:
//   0.05 is a rank swap between methods 5% of the typical value apart).
// Cells whose real value or prediction is not finite, or whose real run diverged (its error is a
// measure of being lost, not of accuracy: a Sage–Husa NEES of 1e11 beside consistent filters near
// 3 would decide any correlation alone), are counted apart and left out of the correlations and
// the MMRV. When every compared value is positive,
// Pearson r is taken on their logarithms: the metrics are ratio scales whose values span orders of magnitude (a
// diverged filter's NEES of 1e11 beside consistent ones near 3 would make r ≈ 1 whatever the rest).
#include <optional>
#include <string>
#include <vector>

namespace locbench::experiments {

struct PredictiveInterval {
  double low = 0.0, median = 0.0, high = 0.0;
  std::size_t runs = 0;
  bool covers(double v) const { return v >= low && v <= high; }
};
// Throws std::invalid_argument for no runs. Non-finite runs sort above every finite one.
PredictiveInterval predictive_interval(std::vector<double> runs);

struct PredictivityCell {
  std::string log, method;
  double real = 0.0;
  bool real_diverged = false;
  PredictiveInterval nominal, extended;
  // The sensor twin's (landmark_sensor_twin: the log's own motion, the fitted sensor), for a
  // metric the sensor moves; none for one of the odometry alone.
  std::optional<PredictiveInterval> sensor;
};

struct TwinPredictivity {
  std::size_t covered = 0;
  // The cells missed, by side: the real value above the interval's high end (for an error, the
  // log fared worse than the twin forecast) and below its low end (better).
  std::size_t above = 0, below = 0;
  double pearson = 0.0, spearman = 0.0, mmrv = 0.0;
};
struct MetricPredictivity {
  std::size_t cells = 0;     // all cells of the metric
  std::size_t compared = 0;  // finite real value and predictions of both twins, real run not diverged
  bool log_scale = false;    // Pearson r on logarithms (every compared value > 0)
  TwinPredictivity nominal, extended;
  // Over the cells with a sensor twin: the ones it covers, and the extended twin's misses split by
  // it — covered by the sensor twin (the motion model missed: with the log's own motion the
  // forecast holds) or missed by it too (the sensor model missed).
  std::size_t sensor_cells = 0, sensor_covered = 0;
  std::size_t extended_misses_of_motion = 0, extended_misses_of_sensor = 0;
};
MetricPredictivity predictivity(const std::vector<PredictivityCell>& cells);

// Which model a real value outside its band [low, high] (a filter's NEES against its χ² band) is
// due to, read from the sensor twin (the log's own motion, the fitted sensor): "motion" when the
// sensor twin's median is itself beyond the band on the same side (with the fitted sensor, the
// log's own motion puts it there), "sensor" when the sensor twin's interval stays on the band's
// side of that bound (with the log's motion the fitted sensor would not: the log's sensor does),
// "both" when the interval straddles it; "" for a real value inside the band.
std::string excess_source(double real, double low, double high, const PredictiveInterval& sensor);

}  // namespace locbench::experiments
