#include "algorithms/pose_correction/ekf_tracker.h"

#include <Eigen/LU>
#include <cmath>

#include "core/angle.h"
#include "core/chi_square.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::pose_correction {
namespace {}  // namespace

// EkfTrackerOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, EkfTrackerOptions& o) {
  v.field("wheel_noise_k_right", o.wheel_noise.k_right, "m", non_negative(), "wheel noise k_R (6.39)");
  v.field("wheel_noise_k_left", o.wheel_noise.k_left, "m", non_negative(), "wheel noise k_L (6.39)");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
  v.field("gate_probability", o.gate_probability, "", closed_open(0.0, 1.0), "χ² gate of a correction (0 = off)");
  v.nested("correction", o.correction, "PoseCorrectionOptions");
}

void validate(const EkfTrackerOptions& o) { validate_fields(o, "EkfTrackerOptions"); }

LOCBENCH_OPTIONS_JSON(EkfTrackerOptions)

EkfTracker::EkfTracker(const EkfTrackerOptions& options, double wheelbase, const Pose2& start)
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      options_(options),
      wheelbase_(wheelbase) {
  validate(options_);
  require_positive_wheelbase(wheelbase, "EkfTracker");
  if (!x_.allFinite()) throw UsageError("EkfTracker: the start pose is not finite");
}

void EkfTracker::predict(const WheelDisplacement& u) {
  // X̂(k/k−1) = F(X̂(k−1)) (6.39); P(k/k−1) = ∇F P ∇Fᵀ + F_Δ Σ_Δ F_Δᵀ (6.40, slides).
  const Pose2 p = to_pose(x_);
  p_ = symmetrize(propagate_covariance(p_, p, u, wheelbase_, options_.wheel_noise));
  x_ = to_vector(odometry_step(p, u, wheelbase_));
}

TrackerUpdate EkfTracker::update(const PoseCorrection& correction) {
  TrackerUpdate out;
  out.correction = correction;
  if (correction.position_fixed) {
    // Eq. 6.41: H = I, ν = Z − X̂ = (Δx, Δy, Δθ).
    Vector3 nu = correction.delta;
    nu(2) = wrap_angle(nu(2));
    const Matrix3 r = symmetrize(correction.covariance);
    const Matrix3 s = p_ + r;
    const Matrix3 s_inv = s.inverse();
    out.innovation = nu;
    out.nis = nu.dot(s_inv * nu);
    out.dof = 3;
    if (options_.gate_probability > 0.0 &&
        out.nis > chi_square_quantile(ChiSquareDof(3.0), options_.gate_probability)) {
      out.gated_out = true;
      return out;
    }
    const Matrix3 k = p_ * s_inv;
    x_ += k * nu;
    x_(2) = wrap_angle(x_(2));
    // Joseph form (I − K)P(I − K)ᵀ + K R Kᵀ, algebraically the thesis's (I − KH)P.
    const Matrix3 i_k = Matrix3::Identity() - k;
    p_ = symmetrize(i_k * p_ * i_k.transpose() + k * r * k.transpose());
    out.kind = TrackerUpdateKind::kFull;
  } else if (correction.heading_fixed) {
    // Eq. 6.42: H = [0 0 1], ν = Δθ.
    const double nu = wrap_angle(correction.delta(2));
    const double r = correction.covariance(2, 2);
    const double s = p_(2, 2) + r;
    out.innovation = {0.0, 0.0, nu};
    out.nis = nu * nu / s;
    out.dof = 1;
    if (options_.gate_probability > 0.0 &&
        out.nis > chi_square_quantile(ChiSquareDof(1.0), options_.gate_probability)) {
      out.gated_out = true;
      return out;
    }
    const Vector3 k = p_.col(2) / s;
    x_ += k * nu;
    x_(2) = wrap_angle(x_(2));
    const Eigen::RowVector3d h_p = p_.row(2);
    p_ = symmetrize(p_ - k * h_p);
    out.kind = TrackerUpdateKind::kHeading;
  }
  return out;
}

TrackerUpdate EkfTracker::correct(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                  const Pose2& sensor_mount) {
  return update(correct_pose(matches, map, pose(), sensor_mount, options_.correction));
}

TrackerUpdate EkfTracker::correct(const Scan& scan, const LineMap& map, const laser::SegmentMatcher& matcher) {
  const laser::MatchResult m = matcher.match(scan, map, pose());
  return correct(m.matches, map, scan.sensor_pose);
}

}  // namespace locbench::pose_correction
