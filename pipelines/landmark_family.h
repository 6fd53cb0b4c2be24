#pragma once
// The filter family on one log: every method of landmark_tracking.h tuned on one part
// of a log and scored on another, with the same grid budget for every method — two tuned
// parameters each: the scale of its process noise over `process_scales`, and its second knob
// (the R scale; the forgetting factor for Sage–Husa and VB-AKF, which estimate R themselves) over
// six values. The setting chosen on the tuning part is, by default ("consistent_log_score"), the
// one with the lowest log score (the mean negative log-likelihood of the truth under the filter's
// estimate and covariance, a proper scoring rule that rewards both a small error and a covariance
// that matches it; a diverged run counts as +∞) among the settings consistent on the tuning part
// (time-averaged NEES inside its χ² band, not diverged), among all settings when none is;
// "log_score" drops the consistency condition; "rmse" takes the lowest position RMSE, with ties
// within `rmse_tolerance` going to the most consistent NEES. It is run on the held-out part from
// the truth's pose at its start.
#include <string>
#include <vector>

#include "algorithms/filters/consistency.h"

#include "pipelines/filter_models.h"
#include "pipelines/landmark_tracking.h"

namespace locbench::experiments::landmarks {

// What picks a method's setting on the tuning part (see the top of this file).
enum class TuningCriterion { kLogScore, kRmse, kConsistentLogScore };
const char* to_string(TuningCriterion c);
TuningCriterion tuning_criterion_from_string(const std::string& s);

struct FamilyOptions {
  std::vector<double> process_scales{1.0 / 64.0, 1.0 / 16.0, 0.25, 1.0, 4.0, 16.0, 64.0};
  std::vector<double> r_scales{0.25, 1.0, 4.0, 16.0, 64.0, 256.0};
  std::vector<double> sage_husa_forgetting{0.9, 0.95, 0.97, 0.98, 0.99, 0.995};
  std::vector<double> vb_forgetting{0.95, 0.97, 0.98, 0.99, 0.995, 0.999};
  Vector3 fixed_q_per_s{0.0025, 0.0025, 0.0025};
  filters::OdometryNoiseOptions adaptive;
  Vector3 initial_sigma{0.02, 0.02, 0.02};
  GatePolicy gate;
  double nees_block_s = 10.0;  // the NEES band counts one independent value per block
  TuningCriterion criterion = TuningCriterion::kConsistentLogScore;
  // With kRmse: settings this close to the lowest RMSE compete on consistency (0: the lowest RMSE
  // alone).
  double rmse_tolerance = 0.0;
  // The diagnosed model's filter carries its sensor's time-correlated noise share as biases in its
  // state (LandmarkSensorModel::structure); false: it takes all of the noise as white.
  bool correlated_sensor_noise = true;
  // The diagnosed model's filter carries its motion noise's time-correlated share
  // (FilterModels::diagnosed_motion_structure) as motion-error states; false: all of it white.
  bool correlated_motion_noise = true;
  // The diagnosed model's filter tracks its sensor's noise level along the log
  // (MethodSetup::level_reference), as the diagnosis measures it varying between blocks
  // (NoiseStructure::range_level_sigma): each setting on the tuning part is run once untracked for
  // its reference innovation level, then tracked; the held-out run keeps the tuned setting's
  // reference.
  bool track_noise_level = false;
};

struct MethodScore {
  Method method = Method::kFixedQ;
  double process_scale = 1.0, knob = 1.0;  // the tuned setting
  double tuning_rmse = 0.0;                // position RMSE of that setting on the tuning part [m]
  double tuning_nees = 0.0;                // its time-averaged NEES there
  double tuning_log_score = 0.0;           // its log score there (TrackResult::log_score)
  bool consistent_setting = false;         // its NEES was inside the band on the tuning part
  std::size_t grid_runs = 0;
  Eigen::Vector2d level_reference = Eigen::Vector2d::Zero();  // MethodSetup::level_reference of the setting
  TrackResult heldout;
};

// The χ² band of a NEES averaged over `duration_s`: K = ⌈duration / nees_block_s⌉ independent
// values, [χ²_{0.025}(3K)/K, χ²_{0.975}(3K)/K].
filters::ChiSquareInterval tuning_nees_band(double duration_s, const FamilyOptions& options);

// One setting of a method's grid, run on the tuning part.
struct GridRun {
  double process_scale = 1.0, knob = 1.0;
  double rmse = 0.0;       // position RMSE [m]; +∞ when the run diverged
  double nees = 0.0;       // time-averaged NEES; +∞ without one
  double log_score = 0.0;  // TrackResult::log_score
};

// The index of the setting `criterion` picks among `runs` (non-empty), `band` being the tuning
// part's NEES band (see the top of this file).
std::size_t choose_setting(const std::vector<GridRun>& runs, const filters::ChiSquareInterval& band,
                           TuningCriterion criterion, double rmse_tolerance = 0.0);

// A part of the tuning data and the models every method runs with there. Cross-fitted tuning
// runs each part with models fitted on another part, so that a setting is judged on data its
// models did not see, as the held-out part will be.
struct TuningPart {
  TrackingData data;
  FilterModels models;
};

// Every method of kMethods tuned over the `tuning` parts (each setting's runs on all parts joined
// into one score) and scored on `test` with `models`.
std::vector<MethodScore> tune_and_score(const std::vector<TuningPart>& tuning, const TrackingData& test,
                                        const FilterModels& models, const FamilyOptions& options);

// Every method of kMethods tuned on `train` and scored on `test`.
std::vector<MethodScore> tune_and_score(const TrackingData& train, const TrackingData& test, const FilterModels& models,
                                        const FamilyOptions& options);

// Dead reckoning on `data`: the logged motion, no observation (scored as the filters are).
TrackResult dead_reckoning(const TrackingData& data, const GatePolicy& gate);

// Every method of `tuned` at its tuned setting on `data` (a held-out part or a twin of it), in
// the order of `tuned`.
std::vector<TrackResult> run_tuned(const TrackingData& data, const std::vector<MethodScore>& tuned,
                                   const FilterModels& models, const FamilyOptions& options);

}  // namespace locbench::experiments::landmarks
