#pragma once
// The indirect Kalman filter of §3.5 (eq. 3.18–3.26) for the wheel-diameter scale errors S_R,
// S_L and the wheelbase error δB. State X = [δx, δy, δθ, S_R, S_L, δB]ᵀ; with Ū = (U_R + U_L)/2
// and θ the odometry heading at the start of the sample, X(k+1) = F(k) X(k) + W(k):
//   δx' = δx − sinθ·Ū·δθ + cosθ·U_R/2·S_R + cosθ·U_L/2·S_L                   (3.20)
//   δy' = δy + cosθ·Ū·δθ + sinθ·U_R/2·S_R + sinθ·U_L/2·S_L                   (3.21)
//   δθ' = δθ + U_R/B·S_R − U_L/B·S_L + (U_L − U_R)/B²·δB                    (3.22)
//   S_R, S_L, δB constant                                                     (3.23)
// (the printed F of eq. 3.25 has seven rows, the S_L row twice; the 6×6 above is eq. 3.20–3.23.)
// Measurement Z = δθ + V (3.26), H = [0 0 1 0 0 0].
//
// Sign convention. The thesis corrects D' = D(1 + S), B' = B + δB (Table 3.3: 88.50 × 1.003607 =
// 88.8192 mm), i.e. the true travel is (1 + S)·U and the true heading increment is
// ((1+S_R)U_R − (1+S_L)U_L)/(B + δB). The δ-dynamics above are then those of
// δ = (pose with the true geometry) − (odometry pose), so the heading measurement is
//   Z = θ_reference − θ_odometry  (compass heading minus the slip-corrected odometry heading).
// (Eq. 3.26 writes Z = θ̂ − θ, with θ̂ "computed with S" — the same quantity.)
//
// Identifiability (ours, see README): Z depends on the parameters only through
// Σ (U_R S_R − U_L S_L)/B − Σ (U_R − U_L)/B² δB, whose δB column is exactly −(1/B)·(S_R column
// + S_L column). Scaling D_L, D_R and B together never changes a heading, so a heading reference
// can never determine more than two combinations: straight runs determine S_R − S_L only,
// turns add S_R + S_L − 2δB/B, and the common scale (S_L = S_R = s, δB = B·s) needs a distance
// reference (e.g. a measured end position: update_position).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "algorithms/calibration/identifiability.h"
#include "core/diff_drive_odometry.h"
#include "core/units.h"

namespace locbench::slip {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct IndirectKfOptions {
  // diag P(0) for [δx, δy, δθ, S_R, S_L, δB] [m², m², rad², 1, 1, m²]: start pose known,
  // diameters within ~1%, wheelbase within ~1 cm.
  Vector6 initial_covariance = (Vector6() << 0.0, 0.0, 0.0, 1e-4, 1e-4, 1e-4).finished();
  // diag Q per sample (ours; the thesis gives none for the IKF): the floor noise of the
  // corridor preset, k = 0.005 √m at 62.5 mm per sample — var(w_d) = 2k²U/4 ≈ 1 mm² per axis,
  // var(w_θ) = 2k²U/B² ≈ (0.5°)² — and constant parameters.
  Vector6 process_noise = (Vector6() << 1e-6, 1e-6, deg(0.5) * deg(0.5), 0.0, 0.0, 0.0).finished();
  double heading_variance = 2.0 * deg(1.0) * deg(1.0);  // R = 2 deg² (as the EKF) [rad²]
};
void to_json(nlohmann::json& j, const IndirectKfOptions& o);
void from_json(const nlohmann::json& j, IndirectKfOptions& o);
// Throws UsageError naming the first field out of its range.
void validate(const IndirectKfOptions& o);

// F(k) of eq. 3.20–3.23 at odometry heading θ.
Matrix6 ikf_transition(const WheelDisplacement& u, double theta, double wheelbase);

struct IkfUpdate {
  double innovation = 0.0;
  double innovation_variance = 0.0;
};

class IndirectKalmanFilter {
 public:
  // Throws UsageError for wheelbase ≤ 0 or invalid options. Starts at X = 0.
  IndirectKalmanFilter(const IndirectKfOptions& options, double wheelbase);

  // X(k/k−1) = F X(k−1), P(k/k−1) = F P Fᵀ + Q; θ = odometry heading at the sample's start.
  void predict(const WheelDisplacement& u, double odometry_heading);
  // Z = θ_reference − θ_odometry (wrapped) [rad] (3.26).
  IkfUpdate update_heading(double z);
  // Ours: a position reference, Z = (x, y)_reference − (x, y)_odometry [m], variance per axis.
  void update_position(const Eigen::Vector2d& z, double variance);

  // Ours: a new run from a known start pose (UMBmark's runs restart at the mark): the pose-error
  // block and its cross-covariances go back to their initial values, the parameters carry over.
  void start_run();

  const Vector6& state() const { return x_; }
  const Matrix6& covariance() const { return p_; }
  double s_right() const { return x_(3); }
  double s_left() const { return x_(4); }
  double delta_b() const { return x_(5); }

 private:
  IndirectKfOptions options_;
  double wheelbase_;
  Vector6 x_ = Vector6::Zero();
  Matrix6 p_;
};

// One sample of a run for the IKF: slip-corrected wheel travel, reference heading at its end.
struct IkfSample {
  WheelDisplacement u;
  std::optional<double> reference_heading;  // [rad]
};

struct IkfRunResult {
  double s_right = 0.0, s_left = 0.0, delta_b = 0.0;
  Vector6 state = Vector6::Zero();
  Matrix6 covariance = Matrix6::Zero();
  std::size_t heading_updates = 0;
};
// Runs the IKF over a run starting at heading `start_heading` (odometry integrates `u` with the
// nominal wheelbase); `end_position_error` (reference − odometry at the end, ours) is applied
// once at the end when given.
IkfRunResult run_indirect_kf(std::span<const IkfSample> samples, double start_heading, const IndirectKfOptions& options,
                             double wheelbase, const std::optional<Eigen::Vector2d>& end_position_error = {},
                             double end_position_variance = 0.0);

// Several runs from known start poses, one filter: the parameters carry over from run to run
// (start_run between them); each run may end with a measured position error.
struct IkfRun {
  std::vector<IkfSample> samples;
  double start_heading = 0.0;
  std::optional<Eigen::Vector2d> end_position_error;
  double end_position_variance = 0.0;
};
IkfRunResult run_indirect_kf(std::span<const IkfRun> runs, const IndirectKfOptions& options, double wheelbase);

// What a run's measurements determine about [S_R, S_L, δB]: the sensitivity of each heading
// measurement (and of the end position, if measured) to the parameters, propagated with
// eq. 3.20–3.23 from δ(0) = 0, stacked into a Jacobian and passed to analyze_identifiability
// with the heading variance (and end-position variance). Parameter names "S_R", "S_L", "dB".
// `relative_tolerance` is on the Fisher-information eigenvalues (1e-6 ⇔ singular values of the
// whitened Jacobian below 1e-3 of the largest count as zero).
calibration::IdentifiabilityReport ikf_identifiability(std::span<const IkfSample> samples, double start_heading,
                                                       double wheelbase, double heading_variance,
                                                       const Eigen::Vector3d& values,
                                                       std::optional<double> end_position_variance = {},
                                                       double relative_tolerance = 1e-6);

}  // namespace locbench::slip
