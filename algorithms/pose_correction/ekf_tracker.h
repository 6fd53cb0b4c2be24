#pragma once
// Position tracking (thesis §6.5, eq. 6.39–6.42): an EKF on X = [x, y, θ]ᵀ whose prediction is
// the differential-drive odometry step (eq. 1.3 = 6.39) with the slides' covariance propagation
// P = ∇F P ∇Fᵀ + F_Δ Σ_Δ F_Δᵀ, Σ_Δ = diag(k_r|U_R|, k_l|U_L|) (the Q of 6.40), and whose
// measurement is the pose correction of a scan (pose_correction.h):
//   position fixed → Z = X̂(k/k−1) + (Δx, Δy, Δθ), H = I₃ (6.41);
//   heading only   → Z = θ̂(k/k−1) + Δθ,        H = [0 0 1] (6.42);
// R = the correction's covariance (the thesis leaves R unspecified). The innovation is the
// correction itself (θ wrapped), so Z − H X̂ needs no map knowledge here.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <span>

#include "algorithms/laser/segment_match.h"
#include "algorithms/pose_correction/pose_correction.h"
#include "core/compass_ekf_model.h"
#include "core/diff_drive_odometry.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::pose_correction {

// Defaults for the thesis's corridor run (§6.6.2: Pioneer 2-DXe, 200 mm/s, encoders and laser
// at 5 Hz, i.e. 40 mm of travel per prediction and one correction per step).
struct EkfTrackerOptions {
  // k_r, k_l of Σ_Δ [m]: 2.5e-5 m is σ = 5 mm per √m of wheel travel, so over the 10 m run the
  // odometry heading σ grows to ≈ 3.9° — enough to cover a Pioneer-like E_d of 1.002 (3.6° of
  // systematic drift over 10 m with B = 0.33 m), which a white-noise model has to absorb.
  WheelNoise wheel_noise{2.5e-5, 2.5e-5};
  // diag P(0) [m², m², rad²]; 0: the start pose is known (the thesis records it).
  Vector3 initial_covariance = Vector3::Zero();
  // Reject a correction whose NIS exceeds the χ²(dof) quantile at this probability; 0 = accept
  // every correction (the thesis has no gate).
  double gate_probability = 0.0;
  PoseCorrectionOptions correction;
};
void to_json(nlohmann::json& j, const EkfTrackerOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, EkfTrackerOptions& o);
void validate(const EkfTrackerOptions& o);

enum class TrackerUpdateKind { kNone, kHeading, kFull };

struct TrackerUpdate {
  TrackerUpdateKind kind = TrackerUpdateKind::kNone;
  bool gated_out = false;                                // a correction existed but its NIS failed the gate
  Eigen::Vector3d innovation = Eigen::Vector3d::Zero();  // (Δx, Δy, Δθ); only Δθ when heading
  double nis = 0.0;                                      // νᵀS⁻¹ν
  int dof = 0;                                           // 3, 1 or 0
  PoseCorrection correction;
};

class EkfTracker : public PoseGaussian {
 public:
  // Throws UsageError for invalid options, wheelbase <= 0 or a non-finite start.
  EkfTracker(const EkfTrackerOptions& options, double wheelbase, const Pose2& start);

  // One odometry sample (eq. 6.39–6.40 and the one-step prediction of §6.5).
  void predict(const WheelDisplacement& u);
  // The measurement update with a correction computed at the current (predicted) estimate.
  TrackerUpdate update(const PoseCorrection& correction);
  // Correction of `matches` at the current estimate, then update.
  TrackerUpdate correct(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& sensor_mount);
  // Matches `scan` against `map` at the current estimate with `matcher`, then corrects.
  TrackerUpdate correct(const Scan& scan, const LineMap& map, const laser::SegmentMatcher& matcher);

 private:
  EkfTrackerOptions options_;
  double wheelbase_;
};

}  // namespace locbench::pose_correction
