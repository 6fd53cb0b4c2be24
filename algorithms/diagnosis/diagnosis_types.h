#pragma once
// The value types of a diagnosis: options, estimates, gains, causes, the report. The steps that
// fill them are in diagnosis.h (orchestration), odometry_channel.h and compass_channel.h.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/diagnosis/landmark_model.h"
#include "algorithms/diagnosis/motion_windows.h"
#include "algorithms/diagnosis/odometry_model.h"
#include "algorithms/diagnosis/residual_tests.h"

namespace locbench::diagnosis {

struct DiagnosisOptions {
  double false_alarm = 0.01;  // per log and channel, divided over the causes tried (Bonferroni)
  WindowOptions windows;
  std::size_t rpe_chain = 10;  // windows chained into one relative-pose segment
  std::size_t block = 10;      // hold-out block length in windows (every third block held out)
  // The odometry fits' Newton steps use the likelihood's exact gradient and Hessian; false: central
  // differences (the tests compare the two). Not a report option (not serialized).
  bool exact_derivatives = true;
};
void to_json(nlohmann::json& j, const DiagnosisOptions& o);
void from_json(const nlohmann::json& j, DiagnosisOptions& o);  // strict: unknown key → UsageError
// Throws UsageError naming the first field out of its range.
void validate(const DiagnosisOptions& o);

struct Estimate {
  std::string name;
  double value = 0.0;
  double lo = 0.0, hi = 0.0;  // 95%
};

struct Gain {
  std::string metric;
  double before = 0.0, after = 0.0;
  double relative() const { return before != 0.0 ? (before - after) / std::abs(before) : 0.0; }
};

struct Cause {
  std::string id;
  std::string channel;  // "odometry", "compass", "landmark" or "histogram"
  bool detected = false;
  std::string statistic = "likelihood_ratio";
  double value = 0.0, threshold = 0.0;
  std::optional<bool> validated;  // LR causes that passed: did they also gain on held-out data?
  std::vector<Estimate> parameters;
  nlohmann::json extra = nlohmann::json::object();  // e.g. region, sensor
  bool identifiable = true;
  std::string explanation;
  std::vector<Gain> gains;  // the first is the cause's primary metric
};

struct Unexplained {
  std::string test, residual, variable;
  double statistic = 0.0, p_value = 1.0, strength = 0.0;
  // Why no catalog cause accounts for it, when one could: e.g. "velocity_scale would explain it
  // but failed the held-out check: the halves disagree, 0.93 [0.92, 0.94] vs 0.88 [0.87, 0.89]".
  std::string reason;
};

struct ConfoundedGroup {
  std::vector<std::string> ids;
  std::string combination;  // what the data determine, e.g. "E_o/E_b = 1.0102 [1.0091, 1.0113]"
  std::string explanation;
};

struct Diagnosis {
  std::string log;
  std::string reference;
  nlohmann::json nominal_model;
  double false_alarm = 0.01;
  std::vector<ResidualTest> residual_tests;
  std::vector<Cause> causes;  // detected first, by evidence; then the rest
  std::vector<std::string> detected;
  std::vector<Unexplained> unexplained;
  // Causes whose likelihood ratio passed on the training windows but that did not improve the
  // held-out windows in their primary metric: not detected, listed for the reader.
  std::vector<std::string> unconfirmed;
  std::vector<ConfoundedGroup> confounded;
  std::vector<std::string> not_testable;  // catalog ids this input cannot show, with why
  std::vector<Gain> overall_gain;         // all kept causes together
  // The white noise floor of the nominal model fitted on the training windows (1σ per window of
  // `noise_window_s` seconds; x along and y left of the window's start heading, θ): what a
  // simulated twin of the log adds to every window besides the kept causes.
  double noise_window_s = 1.0;
  double noise_sigma_x = 0.0, noise_sigma_y = 0.0, noise_sigma_theta = 0.0;
  std::string verdict;
  // The fitted final models, for a filter to use (report: "models"). Odometry: the nominal model
  // extended by the detected (held-out validated) odometry causes only, its σ per window of
  // `noise_window_s` seconds fitted with them; `odometry_kind` says how to read it ("encoder":
  // E_d, E_b, E_o act on the counts; "velocity": the scale and turn-rate parameters act on the
  // logged velocities). Landmark: the nominal range-bearing model extended by the detected
  // landmark causes, σ_r, σ_b fitted (nullopt when the log has no landmarks, map or truth).
  std::optional<OdometryModel> odometry_model;
  std::string odometry_kind;
  std::optional<LandmarkModel> landmark_model;
};

}  // namespace locbench::diagnosis
