#include "baselines/laser/pl_icp.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "baselines/laser/angular_index.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/linear_algebra.h"
#include "core/option_fields.h"
#include "core/pose_observability.h"

namespace locbench::baselines::laser {
namespace {

// The valid beams' end points in the robot frame, in beam order.
std::vector<Eigen::Vector2d> robot_points(const Scan& scan) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (scan.valid(i)) out.push_back(scan.sensor_pose * scan.point(i));
  }
  return out;
}

struct Correspondence {
  std::size_t current = 0;                              // index into the current points
  Eigen::Vector2d reference = Eigen::Vector2d::Zero();  // p_j1
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();     // of the line j1–j2 (point-to-line)
  double error = 0.0;                                   // |e_i| under the current estimate
};

// A fingerprint of a correspondence set (FNV-1a over each pair's current index, reference point
// and line normal): the same set gives the same value.
std::uint64_t fingerprint(const std::vector<Correspondence>& cs) {
  std::uint64_t h = 14695981039346656037ull;
  const auto mix = [&h](std::uint64_t v) {
    h ^= v;
    h *= 1099511628211ull;
  };
  for (const Correspondence& c : cs) {
    mix(c.current);
    for (double v : {c.reference.x(), c.reference.y(), c.normal.x(), c.normal.y()})
      mix(std::bit_cast<std::uint64_t>(v));
  }
  return h;
}

// The line through reference point j1 (point-to-line, step 2 of pl_icp.h).
struct ReferenceLine {
  bool valid = false;  // j1 has a beam-order neighbour that is not across a depth jump
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
};

// With `line_points` > 2 the least-squares line of j1's beam-order neighbourhood (none across a
// depth jump), or the segment to its one neighbour when the neighbourhood has two points: it
// does not depend on the query point, so it is computed once per reference point and call.
std::vector<ReferenceLine> neighbourhood_lines(const std::vector<Eigen::Vector2d>& ref, const PlIcpOptions& o) {
  std::vector<ReferenceLine> lines(ref.size());
  const auto half = static_cast<std::size_t>(o.line_points / 2);
  const auto near = [&](std::size_t a, std::size_t b) { return (ref[a] - ref[b]).norm() <= o.max_neighbour_gap; };
  for (std::size_t j1 = 0; j1 < ref.size(); ++j1) {
    std::size_t lo = j1, hi = j1;
    while (j1 - lo < half && lo > 0 && near(lo - 1, lo)) --lo;
    while (hi - j1 < half && hi + 1 < ref.size() && near(hi + 1, hi)) ++hi;
    if (hi == lo) continue;
    ReferenceLine& line = lines[j1];
    line.valid = true;
    Eigen::Vector2d dir = (ref[lo == j1 ? hi : lo] - ref[j1]).normalized();
    Eigen::Vector2d origin = ref[j1];
    if (hi - lo + 1 >= 3) {
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (std::size_t k = lo; k <= hi; ++k) mean += ref[k];
      mean /= static_cast<double>(hi - lo + 1);
      Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
      for (std::size_t k = lo; k <= hi; ++k) cov += (ref[k] - mean) * (ref[k] - mean).transpose();
      dir = linalg::symmetric_eigen2(cov).vectors.col(1);
      origin = mean;
    }
    line.normal = {-dir.y(), dir.x()};
    line.origin = origin;
  }
  return lines;
}

// Correspondences of the current points under `motion`, trimmed (step 2–3 of pl_icp.h). `lines`:
// neighbourhood_lines (with line_points > 2), else empty.
std::vector<Correspondence> correspondences(const std::vector<Eigen::Vector2d>& ref, const AngularIndex& index,
                                            const std::vector<ReferenceLine>& lines,
                                            const std::vector<Eigen::Vector2d>& cur, const Pose2& motion,
                                            const PlIcpOptions& o) {
  std::vector<Correspondence> out;
  out.reserve(cur.size());
  const double max_d2 = o.max_correspondence_distance * o.max_correspondence_distance;
  const double cos_t = std::cos(motion.theta), sin_t = std::sin(motion.theta);
  for (std::size_t i = 0; i < cur.size(); ++i) {
    const Eigen::Vector2d& p = cur[i];
    const Eigen::Vector2d q(motion.x + cos_t * p.x() - sin_t * p.y(), motion.y + sin_t * p.x() + cos_t * p.y());
    std::size_t j1 = 0;
    double d2 = 0.0;
    if (!index.nearest(q, max_d2, j1, d2)) continue;
    Correspondence c;
    c.current = i;
    c.reference = ref[j1];
    if (o.metric == IcpMetric::kPointToLine && !lines.empty()) {
      const ReferenceLine& line = lines[j1];
      if (!line.valid) continue;
      c.normal = line.normal;
      c.reference = line.origin;
      c.error = std::abs(c.normal.dot(q - line.origin));
    } else if (o.metric == IcpMetric::kPointToLine) {
      // j2: the beam-order neighbour of j1 nearer to q, if it is not across a depth jump.
      double best = std::numeric_limits<double>::infinity();
      std::size_t j2 = j1;
      for (const std::size_t n : {j1 - 1, j1 + 1}) {
        if (n >= ref.size() || (ref[n] - ref[j1]).norm() > o.max_neighbour_gap) continue;
        const double d = (ref[n] - q).squaredNorm();
        if (d < best) {
          best = d;
          j2 = n;
        }
      }
      if (j2 == j1) continue;
      const Eigen::Vector2d dir = (ref[j2] - ref[j1]).normalized();
      c.normal = {-dir.y(), dir.x()};
      c.error = std::abs(c.normal.dot(q - ref[j1]));
    } else {
      c.error = std::sqrt(d2);
    }
    out.push_back(c);
  }
  // Keep the keep_fraction with the smallest errors.
  const auto keep = static_cast<std::size_t>(std::ceil(o.keep_fraction * static_cast<double>(out.size())));
  if (keep < out.size()) {
    std::nth_element(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(keep), out.end(),
                     [](const Correspondence& a, const Correspondence& b) { return a.error < b.error; });
    out.resize(keep);
  }
  return out;
}

struct NormalEquations {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();  // JᵀJ
  Eigen::Vector3d g = Eigen::Vector3d::Zero();  // Jᵀe
  double ss = 0.0;                              // Σ eᵀe
  std::size_t rows = 0;
};

NormalEquations normal_equations(const std::vector<Correspondence>& cs, const std::vector<Eigen::Vector2d>& cur,
                                 const Pose2& motion, IcpMetric metric) {
  NormalEquations n;
  const double cos_t = std::cos(motion.theta), sin_t = std::sin(motion.theta);
  for (const Correspondence& c : cs) {
    const Eigen::Vector2d& p = cur[c.current];
    const Eigen::Vector2d rq(cos_t * p.x() - sin_t * p.y(), sin_t * p.x() + cos_t * p.y());
    const Eigen::Vector2d e2 = rq + motion.translation() - c.reference;
    const Eigen::Vector2d d_theta(-rq.y(), rq.x());  // ∂(R q)/∂θ
    if (metric == IcpMetric::kPointToLine) {
      const Eigen::Vector3d j(c.normal.x(), c.normal.y(), c.normal.dot(d_theta));
      const double e = c.normal.dot(e2);
      n.h += j * j.transpose();
      n.g += j * e;
      n.ss += e * e;
      n.rows += 1;
    } else {
      const Eigen::Vector3d jx(1.0, 0.0, d_theta.x()), jy(0.0, 1.0, d_theta.y());
      n.h += jx * jx.transpose() + jy * jy.transpose();
      n.g += jx * e2.x() + jy * e2.y();
      n.ss += e2.squaredNorm();
      n.rows += 2;
    }
  }
  return n;
}

const char* const kMetricNames[] = {"point_to_line", "point_to_point"};

}  // namespace

const char* to_string(IcpMetric m) { return kMetricNames[m == IcpMetric::kPointToLine ? 0 : 1]; }

IcpMetric icp_metric_from_string(const std::string& s) {
  if (s == "point_to_line") return IcpMetric::kPointToLine;
  if (s == "point_to_point") return IcpMetric::kPointToPoint;
  throw UsageError("PlIcpOptions.metric: expected \"point_to_line\" or \"point_to_point\", found \"" + s + "\"");
}

// PlIcpOptions' fields, stated once (the header explains each).
template <class V>
void visit_fields(V& v, PlIcpOptions& o) {
  v.choice("metric", o.metric, to_string, icp_metric_from_string, "point-to-line or point-to-point");
  v.field("max_iterations", o.max_iterations, "", at_least(1), "ICP iterations");
  v.field("max_correspondence_distance", o.max_correspondence_distance, "m", positive(),
          "largest point-to-match distance");
  v.field("keep_fraction", o.keep_fraction, "", open_closed(0.0, 1.0), "trimmed fraction of correspondences kept");
  v.field("max_neighbour_gap", o.max_neighbour_gap, "m", positive(), "largest gap between a line's two points");
  v.field("line_points", o.line_points, "", at_least(2), "points of a reference line");
  v.field("translation_tolerance", o.translation_tolerance, "m", positive(), "converged below this step");
  v.field("rotation_tolerance", o.rotation_tolerance, "rad", positive(), "converged below this step");
  v.field("degenerate_ratio", o.degenerate_ratio, "", closed_open(0.0, 1.0),
          "eigenvalue ratio of a degenerate direction");
  v.field("min_correspondences", o.min_correspondences, "", at_least(3), "fewer → no correction");
  v.field("min_point_sigma", o.min_point_sigma, "m", positive(), "σ floor of a point");
}

void validate(const PlIcpOptions& o) { validate_fields(o, "PlIcpOptions"); }

LOCBENCH_OPTIONS_JSON(PlIcpOptions)

PlIcpResult pl_icp(const Scan& reference, const Scan& current, const Pose2& initial, const PlIcpOptions& options) {
  validate(options);
  if (!std::isfinite(initial.x) || !std::isfinite(initial.y) || !std::isfinite(initial.theta)) {
    throw UsageError("pl_icp: the initial guess is not finite");
  }
  PlIcpResult out;
  out.motion = initial;
  const std::vector<Eigen::Vector2d> ref = robot_points(reference);
  const std::vector<Eigen::Vector2d> cur = robot_points(current);
  const auto min_n = static_cast<std::size_t>(options.min_correspondences);
  if (ref.size() < 2 || cur.size() < min_n) return out;
  // Length that makes θ comparable with x, y: the rms distance of the current points.
  double ss = 0.0;
  for (const auto& p : cur) ss += p.squaredNorm();
  const double length = std::max(std::sqrt(ss / static_cast<double>(cur.size())), 0.1);

  const AngularIndex index(ref);
  const std::vector<ReferenceLine> lines = options.metric == IcpMetric::kPointToLine && options.line_points > 2
                                               ? neighbourhood_lines(ref, options)
                                               : std::vector<ReferenceLine>{};
  Pose2 motion = initial;
  std::vector<Correspondence> cs;
  std::vector<std::uint64_t> seen;  // the correspondence sets of the earlier iterations
  for (int it = 0; it < options.max_iterations; ++it) {
    cs = correspondences(ref, index, lines, cur, motion, options);
    out.iterations = it + 1;
    if (cs.size() < min_n) return out;  // valid = false, motion = initial
    // A set of correspondences met before means the iterations cycle (the trimming swaps the same
    // points in and out): stop, as CSM does with its correspondence hashes (icp.c), instead of
    // running to max_iterations. Measured on the 1,773 Intel pairs of laser/real_logs: 8.7% of
    // them ran to the 50-iteration cap before.
    const std::uint64_t h = fingerprint(cs);
    if (std::find(seen.begin(), seen.end(), h) != seen.end()) {
      out.converged = true;
      out.cycled = true;
      break;
    }
    seen.push_back(h);
    const NormalEquations n = normal_equations(cs, cur, motion, options.metric);
    const PoseObservability obs = pose_observability(n.h, length, options.degenerate_ratio);
    // Gauss–Newton step in the observable directions only (scaled units).
    const Eigen::Vector3d g = obs.scale * n.g;
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      if (!obs.observable[static_cast<std::size_t>(k)]) continue;
      step -= obs.vectors.col(k) * (obs.vectors.col(k).dot(g) / obs.values[k]);
    }
    step = obs.scale * step;
    motion = Pose2(motion.x + step.x(), motion.y + step.y(), wrap_angle(motion.theta + step.z()));
    if (std::hypot(step.x(), step.y()) < options.translation_tolerance &&
        std::abs(step.z()) < options.rotation_tolerance) {
      out.converged = true;
      break;
    }
  }
  // Covariance at the result, on the last correspondences.
  const NormalEquations n = normal_equations(cs, cur, motion, options.metric);
  const PoseObservability obs = pose_observability(n.h, length, options.degenerate_ratio);
  const double dof = static_cast<double>(n.rows) - 3.0;
  out.residual_rms = std::sqrt(n.ss / static_cast<double>(std::max<std::size_t>(n.rows, 1)));
  const double s2 = std::max(dof > 0.0 ? n.ss / dof : 0.0, options.min_point_sigma * options.min_point_sigma);
  Eigen::Matrix3d inv = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (obs.observable[static_cast<std::size_t>(k)]) {
      inv += obs.vectors.col(k) * obs.vectors.col(k).transpose() / obs.values[k];
    }
  }
  out.covariance = 2.0 * s2 * obs.scale * inv * obs.scale;  // both scans' noise (pl_icp.h)
  if (obs.degenerate) {
    const double inf = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (obs.observable[static_cast<std::size_t>(k)]) continue;
      for (int i = 0; i < 3; ++i) {
        if (std::abs(obs.vectors(i, k)) < 0.1) continue;  // mostly along other axes
        out.covariance.row(i).setZero();
        out.covariance.col(i).setZero();
        out.covariance(i, i) = inf;
      }
    }
  }
  out.degenerate = obs.degenerate;
  out.correspondences = cs.size();
  out.motion = motion;
  out.valid = true;
  return out;
}

}  // namespace locbench::baselines::laser
