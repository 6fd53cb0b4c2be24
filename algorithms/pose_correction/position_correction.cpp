#include "algorithms/pose_correction/position_correction.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "algorithms/pose_correction/input_checks.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::pose_correction {
namespace {

const char* method_name(PositionMethod m) {
  return m == PositionMethod::kPointToLine ? "point_to_line" : "point_to_point";
}

PositionMethod method_from_name(const std::string& s) {
  if (s == "point_to_line") return PositionMethod::kPointToLine;
  if (s == "point_to_point") return PositionMethod::kPointToPoint;
  throw UsageError(
      "PositionOptions.method: expected \"point_to_line\" or \"point_to_point\", "
      "found \"" +
      s + "\"");
}

// Angle between two lines given their normal directions, in [0, π/2].
double line_angle(double beta_a, double beta_b) { return std::abs(0.5 * wrap_angle(2.0 * (beta_a - beta_b))); }

}  // namespace

// PositionOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, PositionOptions& o) {
  v.choice("method", o.method, method_name, method_from_name, "point-to-line or point-to-point");
  v.field("min_angle_spread", o.min_angle_spread, "rad", open_closed(0.0, deg(90.0)),
          "spread of segment directions needed");
  v.field("max_incidence", o.max_incidence, "rad", open(0.0, deg(90.0)), "largest incidence of a point");
  v.field("min_points", o.min_points, "", at_least(1), "segments with fewer points are ignored");
  v.field("min_point_sigma", o.min_point_sigma, "m", positive(), "σ floor of a point");
}

void validate(const PositionOptions& o) { validate_fields(o, "PositionOptions"); }

LOCBENCH_OPTIONS_JSON(PositionOptions)

PositionNormalEquations position_normal_equations(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                                  const Pose2& pose, const Pose2& sensor_mount,
                                                  const PositionOptions& options) {
  validate(options);
  const double beam_heading = pose.theta + sensor_mount.theta;
  const double min_cos = std::cos(options.max_incidence);
  const Eigen::Vector2d t = pose.translation();
  PositionNormalEquations eq;
  std::vector<double> betas;
  for (const auto& m : matches) {
    const Segment& segment = matched_segment(m, map, "correct_position");
    if (m.points.size() < static_cast<std::size_t>(options.min_points)) continue;
    const LineParams line = segment.line();
    const double c = std::cos(line.beta), s = std::sin(line.beta);
    const Eigen::Vector2d n(c, s);
    for (const auto& p : m.points) {
      const Eigen::Vector2d world = pose * p.robot;  // eq. 6.21
      const double r = n.dot(world) - line.rho;
      double w = 1.0;
      if (options.method == PositionMethod::kPointToPoint) {
        // θ_ij: angle between the beam and the line normal (6.34), capped.
        const double cos_inc = std::max(std::abs(std::cos(beam_heading + p.bearing - line.beta)), min_cos);
        w = 1.0 / (cos_inc * cos_inc);  // cos⁻² θ_ij (6.35)
      }
      eq.k1 += w * c * r;
      eq.k2 += w * s * r;
      eq.k3 += w * c * c;
      eq.k4 += w * c * s;
      eq.k5 += w * s * s;
      eq.weighted_ss += w * r * r;
      // ∂world/∂θ = J (world − t), J the +90° rotation; ∂r/∂θ = nᵀ J (world − t).
      const Eigen::Vector2d arm = world - t;
      const double dr = n.dot(Eigen::Vector2d(-arm.y(), arm.x()));
      eq.dk_dtheta += w * dr * n;
      ++eq.points;
    }
    ++eq.segments;
    betas.push_back(line.beta);
  }
  for (std::size_t i = 0; i < betas.size(); ++i) {
    for (std::size_t j = i + 1; j < betas.size(); ++j) {
      eq.angle_spread = std::max(eq.angle_spread, line_angle(betas[i], betas[j]));
    }
  }
  return eq;
}

PositionCorrection correct_position(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& pose,
                                    const Pose2& sensor_mount, const PositionOptions& options) {
  const PositionNormalEquations eq = position_normal_equations(matches, map, pose, sensor_mount, options);
  PositionCorrection out;
  out.angle_spread = eq.angle_spread;
  out.segments_used = eq.segments;
  out.points_used = eq.points;
  if (eq.segments < 2 || eq.angle_spread < options.min_angle_spread) return out;
  const double det = eq.k3 * eq.k5 - eq.k4 * eq.k4;
  // Numerical guard in addition to the angle criterion (cannot trigger for spread ≥ 10° with
  // well-formed input, but keeps NaNs out).
  if (!(det > 1e-12 * (eq.k3 + eq.k5) * (eq.k3 + eq.k5))) return out;
  // Cramer's rule on eq. 6.26 / 6.37.
  out.delta = {(eq.k1 * eq.k5 - eq.k2 * eq.k4) / (eq.k4 * eq.k4 - eq.k3 * eq.k5),
               (eq.k2 * eq.k3 - eq.k1 * eq.k4) / (eq.k4 * eq.k4 - eq.k3 * eq.k5)};
  const Eigen::Matrix2d a_inv = eq.matrix().inverse();
  // Σ w r² at the solution: ss0 + 2Δᵀk + ΔᵀAΔ = ss0 + Δᵀk (since AΔ = −k).
  const double ss = std::max(eq.weighted_ss + out.delta.dot(Eigen::Vector2d(eq.k1, eq.k2)), 0.0);
  const double dof = static_cast<double>(eq.points) - 2.0;
  out.residual_sigma = dof > 0.0 ? std::sqrt(ss / dof) : 0.0;
  const double s2 =
      std::max(out.residual_sigma * out.residual_sigma, options.min_point_sigma * options.min_point_sigma);
  out.covariance = s2 * a_inv;
  // Δ(θ) = −A⁻¹ k(θ) ⇒ ∂Δ/∂θ = −A⁻¹ ∂k/∂θ (weights held fixed).
  out.heading_sensitivity = -a_inv * eq.dk_dtheta;
  out.fixed = true;
  return out;
}

}  // namespace locbench::pose_correction
