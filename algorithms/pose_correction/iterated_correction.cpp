#include "algorithms/pose_correction/iterated_correction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "algorithms/pose_correction/input_checks.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"
#include "core/pose_observability.h"

namespace locbench::pose_correction {
namespace {

struct PointOnLine {
  Eigen::Vector2d robot;   // the scan point, robot frame
  Eigen::Vector2d normal;  // (cos β, sin β) of its map line
  double rho = 0.0;
  std::size_t segment = 0;
};

std::vector<PointOnLine> points_on_lines(std::span<const laser::SegmentMatch> matches, const LineMap& map) {
  std::vector<PointOnLine> out;
  std::size_t n = 0;
  for (const auto& m : matches) n += m.points.size();
  out.reserve(n);
  for (const auto& m : matches) {
    const Segment& segment = matched_segment(m, map, "iterated_point_to_line");
    const LineParams line = segment.line();
    const Eigen::Vector2d normal(std::cos(line.beta), std::sin(line.beta));
    for (const auto& p : m.points) out.push_back({p.robot, normal, line.rho, m.map_segment});
  }
  return out;
}

// A point's |residual| and its index in the points: trimming moves these, not the points.
struct Ranked {
  double abs_residual;
  std::size_t index;
};

// The keep_fraction of `pts` with the smallest |r| under `pose`, as indices into `pts` (in
// `kept`, whose storage is reused from call to call).
void trim(const std::vector<PointOnLine>& pts, const Pose2& pose, double keep_fraction, std::vector<Ranked>& kept) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);  // once, not per point
  kept.resize(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const PointOnLine& p = pts[i];
    const Eigen::Vector2d q(pose.x + c * p.robot.x() - s * p.robot.y(),
                            pose.y + s * p.robot.x() + c * p.robot.y());  // = pose * p.robot
    kept[i] = {std::abs(p.normal.dot(q) - p.rho), i};
  }
  const auto keep = static_cast<std::size_t>(std::ceil(keep_fraction * static_cast<double>(pts.size())));
  if (keep >= pts.size()) return;
  std::nth_element(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(keep), kept.end(),
                   [](const Ranked& a, const Ranked& b) { return a.abs_residual < b.abs_residual; });
  kept.resize(keep);
}

struct Normal {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double ss = 0.0;
};

// JᵀJ, Jᵀr and Σr² over the kept points with J_i = (n_x, n_y, nᵀ ∂(R p)/∂θ): the six distinct
// entries of the symmetric JᵀJ summed as scalars (the same sums, in the same order, as j jᵀ).
Normal normal_equations(const std::vector<PointOnLine>& pts, const std::vector<Ranked>& kept, const Pose2& pose) {
  Normal n;
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  double h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0, g0 = 0, g1 = 0, g2 = 0, ss = 0;
  for (const Ranked& k : kept) {
    const PointOnLine& p = pts[k.index];
    const double rx = c * p.robot.x() - s * p.robot.y(), ry = s * p.robot.x() + c * p.robot.y();
    const double nx = p.normal.x(), ny = p.normal.y();
    const double r = nx * (rx + pose.x) + ny * (ry + pose.y) - p.rho;
    const double jt = nx * -ry + ny * rx;
    h00 += nx * nx;
    h01 += nx * ny;
    h02 += nx * jt;
    h11 += ny * ny;
    h12 += ny * jt;
    h22 += jt * jt;
    g0 += nx * r;
    g1 += ny * r;
    g2 += jt * r;
    ss += r * r;
  }
  n.h << h00, h01, h02, h01, h11, h12, h02, h12, h22;
  n.g << g0, g1, g2;
  n.ss = ss;
  return n;
}

// How many map segments the kept points lie on.
std::size_t distinct_segments(const std::vector<PointOnLine>& pts, const std::vector<Ranked>& kept) {
  std::size_t end = 0;
  for (const PointOnLine& p : pts) end = std::max(end, p.segment + 1);
  std::vector<char> seen(end, 0);
  std::size_t count = 0;
  for (const Ranked& k : kept) {
    char& s = seen[pts[k.index].segment];
    count += s == 0 ? 1 : 0;
    s = 1;
  }
  return count;
}

double rms_range(const std::vector<PointOnLine>& pts) {
  double ss = 0.0;
  for (const auto& p : pts) ss += p.robot.squaredNorm();
  return std::max(std::sqrt(ss / static_cast<double>(std::max<std::size_t>(pts.size(), 1))), 0.1);
}

}  // namespace

// IteratedCorrectionOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, IteratedCorrectionOptions& o) {
  v.field("max_iterations", o.max_iterations, "", at_least(1), "outer: match + solve");
  v.field("inner_steps", o.inner_steps, "", at_least(1), "Gauss–Newton steps per set of matches");
  v.field("translation_tolerance", o.translation_tolerance, "m", positive(), "converged below this step");
  v.field("rotation_tolerance", o.rotation_tolerance, "rad", positive(), "converged below this step");
  v.field("keep_fraction", o.keep_fraction, "", open_closed(0.0, 1.0), "trimmed fraction of residuals kept");
  v.field("degenerate_ratio", o.degenerate_ratio, "", closed_open(0.0, 1.0),
          "eigenvalue ratio of a degenerate direction");
  v.field("min_points", o.min_points, "", at_least(3), "fewer matched points → no correction");
  v.field("min_point_sigma", o.min_point_sigma, "m", positive(), "σ floor of a point");
}

void validate(const IteratedCorrectionOptions& o) { validate_fields(o, "IteratedCorrectionOptions"); }

LOCBENCH_OPTIONS_JSON(IteratedCorrectionOptions)

namespace {

// The Gauss–Newton steps of solve_point_to_line on the points of one set of matches; nullopt
// when there are fewer than min_points.
struct Steps {
  Pose2 pose;
  std::vector<PointOnLine> all;
  double length = 0.0;
};
std::optional<Steps> gauss_newton(std::span<const laser::SegmentMatch> matches, const LineMap& map, const Pose2& pose,
                                  const IteratedCorrectionOptions& options) {
  std::vector<PointOnLine> all = points_on_lines(matches, map);
  if (all.size() < static_cast<std::size_t>(options.min_points)) return std::nullopt;
  const double length = rms_range(all);
  Pose2 x = pose;
  std::vector<Ranked> kept;
  for (int step = 0; step < options.inner_steps; ++step) {
    trim(all, x, options.keep_fraction, kept);
    const Normal n = normal_equations(all, kept, x);
    const PoseObservability e = pose_observability(n.h, length, options.degenerate_ratio);
    const Eigen::Vector3d g = e.scale * n.g;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < 3; ++k) {
      if (!e.observable[k]) continue;
      const auto col = e.vectors.col(static_cast<Eigen::Index>(k));
      d -= col * (col.dot(g) / e.values[static_cast<Eigen::Index>(k)]);
    }
    d = e.scale * d;
    x = Pose2(x.x + d.x(), x.y + d.y(), wrap_angle(x.theta + d.z()));
    if (std::hypot(d.x(), d.y()) < 0.1 * options.translation_tolerance &&
        std::abs(d.z()) < 0.1 * options.rotation_tolerance) {
      break;
    }
  }
  return Steps{x, std::move(all), length};
}

// The result at the pose the steps reached: trimmed residuals, covariance, observability.
IteratedCorrection finish(Steps st, const IteratedCorrectionOptions& options) {
  IteratedCorrection out;
  const Pose2 x = st.pose;
  const double length = st.length;
  std::vector<Ranked> kept;
  trim(st.all, x, options.keep_fraction, kept);
  const Normal n = normal_equations(st.all, kept, x);
  const PoseObservability e = pose_observability(n.h, length, options.degenerate_ratio);
  const double dof = static_cast<double>(kept.size()) - 3.0;
  out.residual_rms = std::sqrt(n.ss / static_cast<double>(kept.size()));
  const double s2 = std::max(dof > 0.0 ? n.ss / dof : 0.0, options.min_point_sigma * options.min_point_sigma);
  Eigen::Matrix3d inv = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < 3; ++k) {
    if (!e.observable[k]) continue;
    const auto col = e.vectors.col(static_cast<Eigen::Index>(k));
    inv += col * col.transpose() / e.values[static_cast<Eigen::Index>(k)];
  }
  out.covariance = s2 * e.scale * inv * e.scale;
  if (e.degenerate) {
    const double inf = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < 3; ++k) {
      if (e.observable[k]) continue;
      for (Eigen::Index i = 0; i < 3; ++i) {
        if (std::abs(e.vectors(i, static_cast<Eigen::Index>(k))) < 0.1) continue;  // mostly along other axes
        out.covariance.row(i).setZero();
        out.covariance.col(i).setZero();
        out.covariance(i, i) = inf;
      }
    }
  }
  out.segments_used = distinct_segments(st.all, kept);
  out.points_used = kept.size();
  out.degenerate = e.degenerate;
  out.corrected = x;
  out.valid = true;
  out.iterations = 1;
  return out;
}

}  // namespace

IteratedCorrection solve_point_to_line(std::span<const laser::SegmentMatch> matches, const LineMap& map,
                                       const Pose2& pose, const IteratedCorrectionOptions& options) {
  validate(options);
  std::optional<Steps> st = gauss_newton(matches, map, pose, options);
  if (!st) {
    IteratedCorrection out;
    out.corrected = pose;
    return out;
  }
  return finish(std::move(*st), options);
}

IteratedCorrection iterated_point_to_line(const laser::SegmentMatcher& matcher, const Scan& scan, const LineMap& map,
                                          const Pose2& estimate, const IteratedCorrectionOptions& options) {
  validate(options);
  IteratedCorrection out = uncorrected<IteratedCorrection>(estimate, "iterated_point_to_line");
  Pose2 pose = estimate;
  // Only the last iteration's covariance and trimmed statistics are returned: they are computed
  // once, after the loop (finish), from that iteration's steps.
  std::optional<Steps> last;
  laser::MatchResult last_matches;
  int iterations = 0;
  bool converged = false;
  for (int it = 0; it < options.max_iterations; ++it) {
    laser::MatchResult m = matcher.match(scan, map, pose);
    iterations = it + 1;
    std::optional<Steps> st = gauss_newton(m.matches, map, pose, options);
    if (!st) {
      // Too few points here: the previous iteration's result stands (none: corrected = estimate,
      // not valid).
      if (last) {
        out = finish(std::move(*last), options);
        out.matches = std::move(last_matches.matches);
      }
      out.iterations = iterations;
      return out;
    }
    const double dt = std::hypot(st->pose.x - pose.x, st->pose.y - pose.y);
    const double dth = std::abs(angle_diff(st->pose.theta, pose.theta));
    pose = st->pose;
    last = std::move(st);
    last_matches = std::move(m);
    if (dt < options.translation_tolerance && dth < options.rotation_tolerance) {
      converged = true;
      break;
    }
  }
  out = finish(std::move(*last), options);
  out.matches = std::move(last_matches.matches);
  out.iterations = iterations;
  out.converged = converged;
  return out;
}

}  // namespace locbench::pose_correction
