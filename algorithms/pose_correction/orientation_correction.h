#pragma once
// Heading correction from matched segments (thesis §6.2, eq. 6.1–6.20).
//
// Sign convention: every Δθ here is the correction to ADD to the estimate's heading so that it
// approaches the truth, Δθ = θ_true − θ_estimate (eq. 6.6: θ̂ = θ + Δθ). Points re-projected
// with a heading that is too large by e lie on lines rotated by +e about the robot, so their
// LS direction minus the map direction is +e and Δθ = map angle − fitted angle = −e.
//
// Per segment: the y-on-x least-squares slope of its points (6.3) against the map direction
// (6.5); for a near-vertical map segment the points are centred, rotated by −90° and refitted
// (6.7–6.11). Combination: Δθ̂ = (HᵀWH)⁻¹HᵀWZ, H = [1 … 1]ᵀ (6.13–6.17), i.e. the weighted mean.
#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "algorithms/laser/segment_match.h"
#include "core/line_map.h"
#include "core/pose2.h"
#include "core/units.h"

namespace locbench::pose_correction {

enum class OrientationWeighting {
  kThesis,           // w_i of eq. 6.18–6.19, negatives clamped to 0, normalised (6.20)
  kEqual,            // w_i = 1/n (eq. 6.12)
  kInverseVariance,  // w_i ∝ 1/var(Δθ_i) from each segment's LS residuals (ours, not the thesis)
};

struct OrientationOptions {
  OrientationWeighting weighting = OrientationWeighting::kThesis;
  // A map segment within this angle of the y axis takes the near-vertical branch (6.7–6.11).
  // The thesis says only "perpendicular or nearly perpendicular to X"; 45° makes the regression
  // always run along the axis of larger spread; 0 disables the branch.
  double near_vertical_within = deg(45.0);
  // Segments with fewer points are ignored (the thesis's matcher already requires 5).
  int min_points = 3;
  // Floor of the per-point perpendicular σ in the variance of Δθ_i [m] (LMS 200: 5 mm, §5.4),
  // so noise-free points do not claim a zero variance.
  double min_point_sigma = mm(5.0);
};
void to_json(nlohmann::json& j, const OrientationOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, OrientationOptions& o);
// Throws UsageError for an invalid option.
void validate(const OrientationOptions& o);

// The heading error one segment implies.
struct SegmentOrientation {
  std::size_t map_segment = 0;
  std::size_t points = 0;
  double delta = 0.0;          // Δθ_i = map angle − fitted angle, in [−π/2, π/2) [rad]
  double variance = 0.0;       // of Δθ_i: σ²_⊥ / Σ(t − t̄)², σ_⊥ from the residuals [rad²]
  bool near_vertical = false;  // the 6.7–6.11 branch was taken
  double thesis_weight = 0.0;  // raw w_i of eq. 6.18 (may be negative or 0 when degenerate)
  double weight = 0.0;         // normalised weight used in the combination (6.20)
};

// Δθ_i of points (world frame, under the estimate) matched to `map_segment` (eq. 6.3–6.11).
// Needs ≥ 2 points with distinct coordinates along the fitted axis (throws UsageError
// otherwise). thesis_weight and weight are left 0.
SegmentOrientation segment_orientation(std::span<const Eigen::Vector2d> world_points, const Segment& map_segment,
                                       const OrientationOptions& options);

// Raw weight of eq. 6.18: w = |p1p2| / |oh| · cos(∠op1p2 − ∠op2p1), with o the scan origin,
// p1, p2 the first and last matched points and h the foot of the perpendicular from o onto
// the line p1p2. Equivalent closed form (derived and tested): with d = |oh| and a, b the signed
// positions of p1, p2 along the line measured from h,
//   cos(∠op1p2 − ∠op2p1) = (d² − ab) / (|op1| |op2|),
// so w = |p1p2|/d for a segment seen symmetrically (a = −b), and w < 0 when ab > d², i.e. the
// whole segment lies to one side of h and is seen obliquely. Returns 0 when |oh| < 1 µm or
// p1 = p2 (degenerate: as |oh| → 0 the weight tends to −∞ with o beyond the segment's end and to
// +∞ with o on the segment, neither of which a laser can see).
double thesis_weight(const Eigen::Vector2d& o, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2);

struct OrientationCorrection {
  bool fixed = false;     // at least one usable segment
  double delta = 0.0;     // Δθ̂ to add to the estimate's heading [rad] (eq. 6.17)
  double variance = 0.0;  // Σ w_i² var(Δθ_i) with the normalised w_i [rad²]
  // kThesis only: every raw weight was ≤ 0 (all segments seen obliquely), so equal weights
  // (6.12) were used instead of discarding the segments.
  bool equal_weight_fallback = false;
  std::vector<SegmentOrientation> segments;  // the usable segments, in match order
};

// Heading correction from matches. World points are recomputed from each point's robot-frame
// coordinates under `estimate` (eq. 5.3), so matches made under another estimate can be used;
// o in the weights is the scan origin, estimate ∘ sensor_mount (the robot centre when the
// laser sits there, as in the thesis). Throws UsageError for a match naming a segment the map
// does not have.
OrientationCorrection correct_orientation(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                          const Pose2& estimate, const Pose2& sensor_mount,
                                          const OrientationOptions& options = {});

}  // namespace locbench::pose_correction
