#include "algorithms/pose_correction/orientation_correction.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "algorithms/pose_correction/input_checks.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::pose_correction {
namespace {

// Line directions are defined modulo π: wrap to [−π/2, π/2).
double wrap_half_turn(double a) { return 0.5 * wrap_angle(2.0 * a); }

// Angle at vertex `at` between the rays to `u` and `v`, in [0, π].
double vertex_angle(const Eigen::Vector2d& at, const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  const Eigen::Vector2d a = u - at, b = v - at;
  return std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
}

const char* weighting_name(OrientationWeighting w) {
  switch (w) {
    case OrientationWeighting::kThesis: return "thesis";
    case OrientationWeighting::kEqual: return "equal";
    case OrientationWeighting::kInverseVariance: return "inverse_variance";
  }
  return "thesis";
}

OrientationWeighting weighting_from_name(const std::string& s) {
  if (s == "thesis") return OrientationWeighting::kThesis;
  if (s == "equal") return OrientationWeighting::kEqual;
  if (s == "inverse_variance") return OrientationWeighting::kInverseVariance;
  throw UsageError(
      "OrientationOptions.weighting: expected \"thesis\", \"equal\" or "
      "\"inverse_variance\", found \"" +
      s + "\"");
}

}  // namespace

// OrientationOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, OrientationOptions& o) {
  v.choice("weighting", o.weighting, weighting_name, weighting_from_name, "weights of the segment headings");
  v.field("near_vertical_within", o.near_vertical_within, "rad", closed(0.0, deg(90.0)), "near-vertical band");
  v.field("min_points", o.min_points, "", at_least(2), "segments with fewer points are ignored");
  v.field("min_point_sigma", o.min_point_sigma, "m", positive(), "σ floor of a point");
}

void validate(const OrientationOptions& o) { validate_fields(o, "OrientationOptions"); }

LOCBENCH_OPTIONS_JSON(OrientationOptions)

SegmentOrientation segment_orientation(std::span<const Eigen::Vector2d> world_points, const Segment& map_segment,
                                       const OrientationOptions& options) {
  const std::size_t n = world_points.size();
  if (n < 2) throw UsageError("segment_orientation: needs at least 2 points");
  const Eigen::Vector2d d = map_segment.p2 - map_segment.p1;
  if (!(d.norm() > 0.0)) throw UsageError("segment_orientation: zero-length map segment");
  // arctan a of eq. 6.5 as a direction angle, so a vertical map segment (a = ∞) is no problem.
  const double map_angle = std::atan2(d.y(), d.x());

  SegmentOrientation s;
  s.points = n;
  // Near-vertical: |angle from the y axis| < near_vertical_within.
  s.near_vertical = std::abs(wrap_half_turn(map_angle - deg(90.0))) < options.near_vertical_within;

  // Centre the points (6.3 / 6.7); in the near-vertical branch rotate them by −90° (6.8):
  // (x, y) → (y, −x).
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : world_points) mean += p;
  mean /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0;
  for (const auto& p : world_points) {
    Eigen::Vector2d q = p - mean;
    if (s.near_vertical) q = Eigen::Vector2d(q.y(), -q.x());
    sxx += q.x() * q.x();
    sxy += q.x() * q.y();
  }
  if (!(sxx > 0.0)) {
    throw UsageError("segment_orientation: the points do not spread along the fitted axis");
  }
  const double slope = sxy / sxx;  // â (6.3) or a₁ (6.10)
  // Fitted direction: arctan â (6.5) or arctan a₁ + 90° (6.11).
  const double fitted = std::atan(slope) + (s.near_vertical ? deg(90.0) : 0.0);
  s.delta = wrap_half_turn(map_angle - fitted);

  // Variance of the fitted direction: σ²_⊥ / Σ(t − t̄)² (first order; equals the y-on-x slope's
  // s²/Sxx mapped through arctan), σ_⊥ from the perpendicular residuals with n − 2 degrees of
  // freedom, floored at min_point_sigma.
  const Eigen::Vector2d dir(std::cos(fitted), std::sin(fitted));
  const Eigen::Vector2d nrm(-dir.y(), dir.x());
  double ss_perp = 0.0, ss_along = 0.0;
  for (const auto& p : world_points) {
    const Eigen::Vector2d q = p - mean;
    ss_perp += std::pow(nrm.dot(q), 2);
    ss_along += std::pow(dir.dot(q), 2);
  }
  const double sigma2 =
      std::max(n > 2 ? ss_perp / static_cast<double>(n - 2) : 0.0, options.min_point_sigma * options.min_point_sigma);
  s.variance = sigma2 / ss_along;
  return s;
}

double thesis_weight(const Eigen::Vector2d& o, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2) {
  const Eigen::Vector2d d = p2 - p1;
  const double len = d.norm();
  if (!(len > 0.0)) return 0.0;
  // |oh|: distance from o to the line p1p2.
  const double oh = std::abs(d.x() * (o.y() - p1.y()) - d.y() * (o.x() - p1.x())) / len;
  if (oh < 1e-6) return 0.0;
  const double at_p1 = vertex_angle(p1, o, p2);  // ∠op1p2
  const double at_p2 = vertex_angle(p2, o, p1);  // ∠op2p1
  return len / oh * std::cos(at_p1 - at_p2);     // eq. 6.18
}

OrientationCorrection correct_orientation(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                          const Pose2& estimate, const Pose2& sensor_mount,
                                          const OrientationOptions& options) {
  validate(options);
  const Eigen::Vector2d origin = (estimate * sensor_mount).translation();
  OrientationCorrection out;
  std::vector<Eigen::Vector2d> world;
  for (const auto& m : matches) {
    const Segment& segment = matched_segment(m, map, "correct_orientation");
    if (m.points.size() < static_cast<std::size_t>(options.min_points)) continue;
    world.clear();
    for (const auto& p : m.points) world.push_back(estimate * p.robot);  // eq. 5.3
    SegmentOrientation s;
    try {
      s = segment_orientation(world, segment, options);
    } catch (const UsageError&) {
      continue;  // all points coincide: no direction
    }
    s.map_segment = m.map_segment;
    s.thesis_weight = thesis_weight(origin, world.front(), world.back());
    out.segments.push_back(s);
  }

  // Raw weights, then normalisation (6.20).
  double total = 0.0;
  for (auto& s : out.segments) {
    switch (options.weighting) {
      case OrientationWeighting::kThesis: s.weight = std::max(s.thesis_weight, 0.0); break;
      case OrientationWeighting::kEqual: s.weight = 1.0; break;
      case OrientationWeighting::kInverseVariance: s.weight = 1.0 / s.variance; break;
    }
    total += s.weight;
  }
  if (options.weighting == OrientationWeighting::kThesis && !(total > 0.0) && !out.segments.empty()) {
    // Every segment seen obliquely (all raw weights ≤ 0): fall back to equal weights (6.12)
    // rather than discard good data.
    out.equal_weight_fallback = true;
    for (auto& s : out.segments) s.weight = 1.0;
    total = static_cast<double>(out.segments.size());
  }
  if (!(total > 0.0) || !std::isfinite(total)) return out;
  // Δθ̂ = (HᵀWH)⁻¹HᵀWZ with H = 1 and W = diag(w) normalised: the weighted mean (6.17).
  // The Z_i are wrapped to [−π/2, π/2) and, for a heading error below 90°, lie together.
  for (auto& s : out.segments) {
    s.weight /= total;
    out.delta += s.weight * s.delta;
    out.variance += s.weight * s.weight * s.variance;
  }
  out.fixed = true;
  return out;
}

}  // namespace locbench::pose_correction
