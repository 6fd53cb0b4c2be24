#pragma once
// The catalog of causes the diagnosis can name: one entry per cause with its channel, its
// parameters (name, unit, plausible range, fit scale), the held-out metric that judges it, the
// residual tests it accounts for, when it applies, and its explanation. A new cause is one entry
// here plus its forward model (odometry_model.h, compass_channel.h or landmark_model.h); the simulator mapping of
// each id is in datasets/sim (the extended scenario a diagnosis writes).
#include <string>
#include <string_view>
#include <vector>

#include "algorithms/diagnosis/diagnosis_types.h"
#include "algorithms/diagnosis/odometry_model.h"

namespace locbench::diagnosis {

// Catalog ids (the report contract).
namespace cause {
inline constexpr std::string_view kWheelDiameterRatio = "wheel_diameter_ratio";
inline constexpr std::string_view kWheelbaseScale = "wheelbase_scale";
inline constexpr std::string_view kMeanDiameterScale = "mean_diameter_scale";
inline constexpr std::string_view kWheelSlip = "wheel_slip";
inline constexpr std::string_view kVelocityScale = "velocity_scale";
inline constexpr std::string_view kSpeedDependentScale = "speed_dependent_scale";
inline constexpr std::string_view kDriveStall = "drive_stall";
inline constexpr std::string_view kTurnRateScale = "turn_rate_scale";
inline constexpr std::string_view kTurnRateBias = "turn_rate_bias";
inline constexpr std::string_view kDriveResponse = "drive_response";
inline constexpr std::string_view kNoiseGrowth = "odometry_noise_growth";
inline constexpr std::string_view kHeavyTails = "heavy_tailed_noise";
inline constexpr std::string_view kTimeOffset = "sensor_time_offset";
inline constexpr std::string_view kEncoderQuantization = "encoder_quantization";
inline constexpr std::string_view kCompassQuantization = "compass_quantization";
inline constexpr std::string_view kCompassBias = "compass_bias";
inline constexpr std::string_view kCompassDisturbance = "compass_disturbance";
inline constexpr std::string_view kLandmarkRangeScale = "landmark_range_scale";
inline constexpr std::string_view kLandmarkRangeBias = "landmark_range_bias";
inline constexpr std::string_view kLandmarkRangeOffAxis = "landmark_range_off_axis_scale";
inline constexpr std::string_view kLandmarkBearingBias = "landmark_bearing_bias";
inline constexpr std::string_view kLandmarkTimeOffset = "landmark_time_offset";
inline constexpr std::string_view kLandmarkRangeNoise = "landmark_range_dependent_noise";
inline constexpr std::string_view kLandmarkTurnNoise = "landmark_turn_dependent_bearing_noise";
inline constexpr std::string_view kLandmarkHeavyTails = "landmark_heavy_tails";
inline constexpr std::string_view kLandmarkPositionError = "landmark_position_error";
}  // namespace cause

// The held-out metric that decides whether a cause is kept: the error component the cause acts
// on (a speed cause must reduce the translation error, a turn cause the heading error), the
// better of the two for causes acting on both, or the predictive likelihood for noise causes.
enum class PrimaryMetric { kTranslation, kHeading, kTranslationOrHeading, kLikelihood, kExact };

struct CauseParameter {
  std::string name;  // report name
  std::string unit;
  double OdometryModel::*field = nullptr;  // odometry causes: the model parameter it sets
  double initial = 0.0;
  double scale = 1.0;  // typical size of a change (finite-difference steps)
  bool positive = false;
  double plausible_lo = 0.0, plausible_hi = 0.0;  // outside: reported as implausible
};

struct CauseSpec {
  std::string_view id;
  std::string_view channel;  // "odometry", "compass" or "landmark"
  std::vector<CauseParameter> params;
  PrimaryMetric metric = PrimaryMetric::kTranslationOrHeading;
  bool noise = false;  // acts on the noise model, not on the mean
  // A generic cause (heavy tails) is tried only after the specific ones have entered: a specific
  // cause (slip) that produces the same symptom is named first.
  bool generic = false;
  // Residual tests it accounts for, as "test:residual" ("heavy_tails:heading").
  std::vector<std::string_view> explains;
  bool (*applies)(const MotionData&) = nullptr;  // nullptr: always (on its channel)
  std::string (*explain)(const Cause&) = nullptr;
};

const std::vector<CauseSpec>& cause_catalog();
// Throws std::logic_error for an id not in the catalog (a programming error).
const CauseSpec& cause_spec(std::string_view id);
// The odometry causes that apply to these data, in catalog order.
std::vector<const CauseSpec*> odometry_causes(const MotionData& d);
// The landmark channel's causes, in catalog order.
std::vector<const CauseSpec*> landmark_causes();
// The catalog explanation of a cause with its fitted parameters filled in.
std::string explain(const Cause& c);
// Does the cause account for this residual test (by name and residual)?
bool accounts_for(const CauseSpec& spec, const ResidualTest& t);
std::string to_string(PrimaryMetric m);

}  // namespace locbench::diagnosis
