#pragma once
// Differential-drive odometry (eq. 1.1–1.3) and its covariance propagation (slides:
// Σ_p' = F_p Σ_p F_pᵀ + F_Δ Σ_Δ F_Δᵀ, Σ_Δ = diag(k_r|ΔU_R|, k_l|ΔU_L|)).
#include <Eigen/Core>
#include <cstdint>

#include "core/pose2.h"
#include "core/robot_params.h"

namespace locbench {

// Wheel travel in one sample [m]: U_L, U_R.
struct WheelDisplacement {
  double left = 0.0;
  double right = 0.0;
};

// Travel of each wheel from encoder count increments under a model.
inline WheelDisplacement displacement_from_ticks(const NominalModel& m, std::int64_t d_left, std::int64_t d_right) {
  return {m.meters_per_tick_left * static_cast<double>(d_left), m.meters_per_tick_right * static_cast<double>(d_right)};
}

// ΔD = (U_L + U_R)/2 and Δθ = (U_R − U_L)/B (eq. 1.1, 1.2).
struct BodyIncrement {
  double distance = 0.0;
  double rotation = 0.0;
};
inline BodyIncrement body_increment(const WheelDisplacement& u, double wheelbase) {
  return {0.5 * (u.left + u.right), (u.right - u.left) / wheelbase};
}

// One odometry step, midpoint integration (eq. 1.3):
// x' = x + ΔD cos(θ + Δθ/2), y' = y + ΔD sin(θ + Δθ/2), θ' = θ + Δθ.
Pose2 odometry_step(const Pose2& p, const WheelDisplacement& u, double wheelbase);

// The same motion integrated exactly along the circular arc the wheel travels describe (the
// truth of a simulator, not limited by the midpoint approximation of eq. 1.3):
// chord = ΔD·sin(Δθ/2)/(Δθ/2) at heading θ + Δθ/2.
Pose2 exact_arc_step(const Pose2& p, const WheelDisplacement& u, double wheelbase);

// Throws UsageError "<who>: wheelbase must be > 0" unless the wheelbase is positive and finite
// (every filter and detector built on the odometry model checks its wheelbase this way).
void require_positive_wheelbase(double wheelbase, const char* who);

// Noise growth coefficients of Σ_Δ: variance of each wheel's travel per metre it travels [m].
struct WheelNoise {
  double k_right = 0.0;
  double k_left = 0.0;
};

using Matrix3 = Eigen::Matrix3d;
using Matrix32 = Eigen::Matrix<double, 3, 2>;

// ∂(pose')/∂(pose), evaluated at the step's start pose.
Matrix3 odometry_jacobian_pose(const Pose2& p, const WheelDisplacement& u, double wheelbase);
// ∂(pose')/∂(U_R, U_L), columns ordered (right, left) as on the slides.
Matrix32 odometry_jacobian_wheels(const Pose2& p, const WheelDisplacement& u, double wheelbase);

// Σ_p' = F_p Σ_p F_pᵀ + F_Δ Σ_Δ F_Δᵀ.
Matrix3 propagate_covariance(const Matrix3& sigma, const Pose2& p, const WheelDisplacement& u, double wheelbase,
                             const WheelNoise& noise);

}  // namespace locbench
