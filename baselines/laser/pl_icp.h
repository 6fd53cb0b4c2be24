#pragma once
// Scan-to-scan registration as the field does it: PL-ICP (Censi, "An ICP variant using a
// point-to-line metric", ICRA 2008), with plain point-to-point ICP (Besl & McKay 1992) as the
// same loop with the other metric, for an independent check.
//
// Given a reference scan, a current scan and a first guess of the current robot pose in the
// reference robot frame (the odometry's relative motion), each iteration:
//   1. transforms the current scan's points with the motion estimate;
//   2. finds each point's nearest reference point j1 (angular_index.h, CSM's ordered search) and, for PL-ICP, the
//      beam-order neighbour j2 of j1 nearer to the point: the point's line is j1–j2 (Censi), or
//      by default the least-squares line of j1's beam-order neighbourhood (`line_points`);
//   3. trims: correspondences farther than `max_correspondence_distance` are dropped, then only
//      the `keep_fraction` with the smallest residuals are kept (robust to clutter and to
//      points the reference did not see);
//   4. takes one Gauss–Newton step on Σ e_iᵀ e_i (e_i = n_iᵀ(R q_i + t − p_j1) for
//      point-to-line, R q_i + t − p_j1 for point-to-point); directions of the 3×3 normal matrix
//      whose eigenvalue is below `degenerate_ratio` × the largest (a corridor's length) are not
//      stepped along, so they keep the first guess;
// until the step is below the tolerances, a set of correspondences recurs (the iterations cycle;
// CSM stops there too), or `max_iterations` is reached.
//
// Covariance: 2 σ̂² H⁻¹ with H = JᵀJ at the result and σ̂² = Σe²/(N − 3) (floored at
// min_point_sigma²) — the inverse Hessian of the cost, doubled because the reference scan is as
// noisy as the current one and its noise enters through the lines, correlated along them (with
// σ̂² alone the spread over 40 noisy room scans was up to 4.7× the reported variance; Censi 2007
// shows the Hessian is optimistic). Degenerate directions get an infinite variance along them.
//
// Only core/ is used (Scan, Pose2), so this baseline shares no code with the thesis's
// matcher.
#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "core/pose2.h"
#include "core/scan.h"
#include "core/units.h"

namespace locbench::baselines::laser {

enum class IcpMetric { kPointToLine, kPointToPoint };
const char* to_string(IcpMetric m);
// "point_to_line" | "point_to_point"; UsageError otherwise.
IcpMetric icp_metric_from_string(const std::string& s);

struct PlIcpOptions {
  IcpMetric metric = IcpMetric::kPointToLine;
  int max_iterations = 50;
  // A correspondence farther than this from its reference point is not one [m] (CSM's
  // max_correspondence_dist is 0.3–0.5 m for indoor SICK logs).
  double max_correspondence_distance = 0.5;
  // Of the remaining correspondences, the fraction with the smallest residuals kept (CSM:
  // outliers_maxPerc 0.9–0.95).
  double keep_fraction = 0.9;
  // Reference neighbours j1, j2 farther apart than this do not form a line (a depth jump);
  // the correspondence is dropped [m].
  double max_neighbour_gap = 0.5;
  // Points defining each correspondence's line: 2 = Censi's segment j1–j2; more = the
  // least-squares line of that many beam-order neighbours centred on j1 (not across a depth
  // jump). With 1° beams and 5 mm noise the two-point normal scatters by ~10° at 2 m, which
  // makes a corridor look as if its length were observable.
  int line_points = 5;
  double translation_tolerance = 1e-5;  // [m] step below which the loop stops
  double rotation_tolerance = 1e-6;     // [rad]
  // Eigenvalue ratio below which a direction counts as unobservable (corridor).
  // 1e-3: a 16 m corridor seen by a 181-beam scan with 5 mm noise has a ratio of ~1e-4 along
  // its length from the normals' noise alone (tested); a door frame seen by 5 of 150 points
  // still gives ~3e-2.
  double degenerate_ratio = 1e-3;
  int min_correspondences = 10;
  double min_point_sigma = mm(5.0);  // floor of σ̂ in the covariance [m] (LMS 200: 5 mm)
};
void to_json(nlohmann::json& j, const PlIcpOptions& o);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, PlIcpOptions& o);
void validate(const PlIcpOptions& o);

struct PlIcpResult {
  Pose2 motion;  // the current robot pose in the reference robot frame
  // Covariance of (x, y, θ) of `motion` [m², m², rad²]; +∞ along degenerate directions.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  bool converged = false;   // the step fell below the tolerances, or the iterations cycled
  bool cycled = false;      // stopped on a correspondence set met in an earlier iteration (CSM)
  bool degenerate = false;  // some direction was left at the first guess
  bool valid = false;       // enough correspondences: false → motion = first guess
  int iterations = 0;
  std::size_t correspondences = 0;  // kept in the last iteration
  double residual_rms = 0.0;        // of the kept residuals [m]
};

// Registers `current` to `reference` from `initial` (current robot pose in the reference robot
// frame). Points go through each scan's sensor_pose into its robot frame. Throws UsageError for
// invalid options or a non-finite initial guess; too few valid points or correspondences →
// valid = false, motion = initial.
PlIcpResult pl_icp(const Scan& reference, const Scan& current, const Pose2& initial, const PlIcpOptions& options = {});

}  // namespace locbench::baselines::laser
