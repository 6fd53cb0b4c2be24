#include "baselines/localization/line_feature_kalman_localizer.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "core/angle.h"
#include "core/chi_square.h"
#include "core/errors.h"
#include "core/linear_algebra.h"
#include "core/option_fields.h"

namespace locbench::baselines::localization {

// LineFeatureKalmanOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, LineFeatureKalmanOptions& o) {
  v.field("wheel_noise_k_right", o.wheel_noise.k_right, "m", non_negative(), "wheel noise k_R");
  v.field("wheel_noise_k_left", o.wheel_noise.k_left, "m", non_negative(), "wheel noise k_L");
  v.field("initial_covariance", o.initial_covariance, "m², m², rad²", non_negative(), "diag P(0)");
  v.field("gate_probability", o.gate_probability, "", open(0.0, 1.0), "χ² validation gate");
}

void validate(const LineFeatureKalmanOptions& o) { validate_fields(o, "LineFeatureKalmanOptions"); }

LOCBENCH_OPTIONS_JSON(LineFeatureKalmanOptions)

double validation_gate(double probability) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw UsageError("validation_gate: probability must be in (0, 1)");
  }
  return chi_square_quantile(ChiSquareDof(2.0), probability);
}

LineFeatureKalmanLocalizer::LineFeatureKalmanLocalizer(const LineFeatureKalmanOptions& options, double wheelbase,
                                                       const Pose2& start)
    : PoseGaussian(to_vector(start), options.initial_covariance.asDiagonal()),
      options_(options),
      wheelbase_(wheelbase),
      gate_(0.0) {
  validate(options_);
  require_positive_wheelbase(wheelbase, "LineFeatureKalmanLocalizer");
  if (!x_.allFinite()) throw UsageError("LineFeatureKalmanLocalizer: the start is not finite");
  gate_ = validation_gate(options_.gate_probability);
}

void LineFeatureKalmanLocalizer::predict(const WheelDisplacement& u) {
  const Pose2 p = to_pose(x_);
  p_ = symmetrize(propagate_covariance(p_, p, u, wheelbase_, options_.wheel_noise));
  x_ = to_vector(odometry_step(p, u, wheelbase_));
}

LineUpdate LineFeatureKalmanLocalizer::associate(std::span<const LineObservation> observations,
                                                 const LineMap& map) const {
  LineUpdate out;
  out.gate = gate_;
  const Pose2 pose = to_pose(x_);
  std::vector<LinePrediction> predicted;
  predicted.reserve(map.segments.size());
  for (const auto& s : map.segments) predicted.push_back(predict_line(s.line(), pose));
  for (std::size_t j = 0; j < observations.size(); ++j) {
    const LineObservation& z = observations[j];
    if (!std::isfinite(z.alpha) || !std::isfinite(z.r) || !z.covariance.allFinite()) {
      throw UsageError("LineFeatureKalmanLocalizer: observation " + std::to_string(j) + " is not finite");
    }
    LinePair best;
    best.mahalanobis2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      const Eigen::Vector2d v = line_innovation(z, predicted[i]);
      const Eigen::Matrix2d s = predicted[i].jacobian * p_ * predicted[i].jacobian.transpose() + z.covariance;
      const Eigen::LDLT<Eigen::Matrix2d> ldlt(s);
      if (ldlt.info() != Eigen::Success || !(s.determinant() > 0.0)) continue;
      const double d2 = v.dot(ldlt.solve(v));
      if (d2 <= gate_ && d2 < best.mahalanobis2) {
        best = {j, i, v, s, d2};
      }
    }
    if (std::isfinite(best.mahalanobis2)) {
      out.pairs.push_back(best);
    } else {
      out.unmatched.push_back(j);
    }
  }
  return out;
}

LineUpdate LineFeatureKalmanLocalizer::update(std::span<const LineObservation> observations, const LineMap& map) {
  LineUpdate out = associate(observations, map);
  const auto m = static_cast<Eigen::Index>(out.pairs.size());
  if (m == 0) return out;
  // Stacked innovation v, Jacobian ∇h and Σ_IN = ∇h Σ_p ∇hᵀ + blockdiag(Σ_R,j).
  const Pose2 pose = to_pose(x_);
  Eigen::VectorXd v(2 * m);
  Eigen::MatrixXd h(2 * m, 3);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const LinePair& pair = out.pairs[static_cast<std::size_t>(k)];
    const LinePrediction pred = predict_line(map.segments[pair.map_segment].line(), pose);
    v.segment<2>(2 * k) = pair.innovation;
    h.block<2, 3>(2 * k, 0) = pred.jacobian;
    r.block<2, 2>(2 * k, 2 * k) = observations[pair.observation].covariance;
  }
  const Eigen::MatrixXd s = h * p_ * h.transpose() + r;
  const Eigen::MatrixXd s_inv = linalg::inverse(s);
  const Eigen::MatrixXd k = p_ * h.transpose() * s_inv;  // K = Σ_p ∇hᵀ Σ_IN⁻¹
  x_ += k * v;
  x_(2) = wrap_angle(x_(2));
  p_ = symmetrize(p_ - k * s * k.transpose());  // Σ_p − K Σ_IN Kᵀ
  return out;
}

}  // namespace locbench::baselines::localization
