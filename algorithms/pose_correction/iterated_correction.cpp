#include "algorithms/pose_correction/iterated_correction.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "algorithms/core/angle.h"
#include "algorithms/core/errors.h"
#include "algorithms/core/json_options.h"

namespace locbench::pose_correction {
namespace {

struct PointOnLine {
  Eigen::Vector2d robot;   // the scan point, robot frame
  Eigen::Vector2d normal;  // (cos β, sin β) of its map line
  double rho = 0.0;
  std::size_t segment = 0;
  double residual = 0.0;
};

std::vector<PointOnLine> points_on_lines(std::span<const laser::SegmentMatch> matches,
                                         const LineMap& map) {
  std::vector<PointOnLine> out;
  for (const auto& m : matches) {
    if (m.map_segment >= map.segments.size()) {
      throw UsageError("iterated_point_to_line: a match names map segment " +
                       std::to_string(m.map_segment) + ", the map has " +
                       std::to_string(map.segments.size()));
    }
    const LineParams line = map.segments[m.map_segment].line();
    for (const auto& p : m.points) {
      out.push_back({p.robot, {std::cos(line.beta), std::sin(line.beta)}, line.rho,
                     m.map_segment, 0.0});
    }
  }
  return out;
}

// Residuals under `pose`, then keep the keep_fraction with the smallest |r|.
void trim(std::vector<PointOnLine>& pts, const Pose2& pose, double keep_fraction) {
  for (auto& p : pts) p.residual = p.normal.dot(pose * p.robot) - p.rho;
  const auto keep =
      static_cast<std::size_t>(std::ceil(keep_fraction * static_cast<double>(pts.size())));
  if (keep >= pts.size()) return;
  std::nth_element(pts.begin(), pts.begin() + static_cast<std::ptrdiff_t>(keep), pts.end(),
                   [](const PointOnLine& a, const PointOnLine& b) {
                     return std::abs(a.residual) < std::abs(b.residual);
                   });
  pts.resize(keep);
}

struct Normal {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double ss = 0.0;
};

Normal normal_equations(const std::vector<PointOnLine>& pts, const Pose2& pose) {
  Normal n;
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  for (const auto& p : pts) {
    const Eigen::Vector2d rp(c * p.robot.x() - s * p.robot.y(), s * p.robot.x() + c * p.robot.y());
    const double r = p.normal.dot(rp + pose.translation()) - p.rho;
    const Eigen::Vector3d j(p.normal.x(), p.normal.y(), p.normal.dot(Eigen::Vector2d(-rp.y(), rp.x())));
    n.h += j * j.transpose();
    n.g += j * r;
    n.ss += r * r;
  }
  return n;
}

struct Eigen3 {
  Eigen::Matrix3d scale;
  Eigen::Vector3d values;
  Eigen::Matrix3d vectors;
  std::array<bool, 3> observable{true, true, true};
  bool degenerate = false;
};

Eigen3 decompose(const Eigen::Matrix3d& h, double length, double ratio) {
  Eigen3 e;
  e.scale = Eigen::Vector3d(1.0, 1.0, 1.0 / length).asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(e.scale * h * e.scale);
  e.values = es.eigenvalues();
  e.vectors = es.eigenvectors();
  const double largest = e.values.maxCoeff();
  for (std::size_t k = 0; k < 3; ++k) {
    e.observable[k] = largest > 0.0 && e.values[static_cast<Eigen::Index>(k)] > ratio * largest;
    e.degenerate = e.degenerate || !e.observable[k];
  }
  return e;
}

double rms_range(const std::vector<PointOnLine>& pts) {
  double ss = 0.0;
  for (const auto& p : pts) ss += p.robot.squaredNorm();
  return std::max(std::sqrt(ss / static_cast<double>(std::max<std::size_t>(pts.size(), 1))), 0.1);
}

}  // namespace

void validate(const IteratedCorrectionOptions& o) {
  if (o.max_iterations < 1) throw UsageError("IteratedCorrectionOptions.max_iterations: must be >= 1");
  if (o.inner_steps < 1) throw UsageError("IteratedCorrectionOptions.inner_steps: must be >= 1");
  if (!(o.translation_tolerance > 0.0) || !(o.rotation_tolerance > 0.0)) {
    throw UsageError("IteratedCorrectionOptions.translation_tolerance, rotation_tolerance: must be > 0");
  }
  if (!(o.keep_fraction > 0.0 && o.keep_fraction <= 1.0)) {
    throw UsageError("IteratedCorrectionOptions.keep_fraction: must be in (0, 1]");
  }
  if (!(o.degenerate_ratio >= 0.0 && o.degenerate_ratio < 1.0)) {
    throw UsageError("IteratedCorrectionOptions.degenerate_ratio: must be in [0, 1)");
  }
  if (o.min_points < 3) throw UsageError("IteratedCorrectionOptions.min_points: must be >= 3");
  if (!(o.min_point_sigma > 0.0) || !std::isfinite(o.min_point_sigma)) {
    throw UsageError("IteratedCorrectionOptions.min_point_sigma: must be > 0 m");
  }
}

void to_json(nlohmann::json& j, const IteratedCorrectionOptions& o) {
  j = {{"max_iterations", o.max_iterations},
       {"inner_steps", o.inner_steps},
       {"translation_tolerance", o.translation_tolerance},
       {"rotation_tolerance", o.rotation_tolerance},
       {"keep_fraction", o.keep_fraction},
       {"degenerate_ratio", o.degenerate_ratio},
       {"min_points", o.min_points},
       {"min_point_sigma", o.min_point_sigma}};
}

void from_json(const nlohmann::json& j, IteratedCorrectionOptions& o) {
  StrictJsonReader r(j, "IteratedCorrectionOptions");
  r.read("max_iterations", o.max_iterations);
  r.read("inner_steps", o.inner_steps);
  r.read("translation_tolerance", o.translation_tolerance);
  r.read("rotation_tolerance", o.rotation_tolerance);
  r.read("keep_fraction", o.keep_fraction);
  r.read("degenerate_ratio", o.degenerate_ratio);
  r.read("min_points", o.min_points);
  r.read("min_point_sigma", o.min_point_sigma);
  r.finish();
  validate(o);
}

IteratedCorrection solve_point_to_line(std::span<const laser::SegmentMatch> matches,
                                       const LineMap& map, const Pose2& pose,
                                       const IteratedCorrectionOptions& options) {
  validate(options);
  IteratedCorrection out;
  out.corrected = pose;
  std::vector<PointOnLine> all = points_on_lines(matches, map);
  if (all.size() < static_cast<std::size_t>(options.min_points)) return out;
  const double length = rms_range(all);
  Pose2 x = pose;
  std::vector<PointOnLine> kept;
  for (int step = 0; step < options.inner_steps; ++step) {
    kept = all;
    trim(kept, x, options.keep_fraction);
    const Normal n = normal_equations(kept, x);
    const Eigen3 e = decompose(n.h, length, options.degenerate_ratio);
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
  kept = all;
  trim(kept, x, options.keep_fraction);
  const Normal n = normal_equations(kept, x);
  const Eigen3 e = decompose(n.h, length, options.degenerate_ratio);
  const double dof = static_cast<double>(kept.size()) - 3.0;
  out.residual_rms = std::sqrt(n.ss / static_cast<double>(kept.size()));
  const double s2 =
      std::max(dof > 0.0 ? n.ss / dof : 0.0, options.min_point_sigma * options.min_point_sigma);
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
  std::vector<std::size_t> segs;
  for (const auto& p : kept) segs.push_back(p.segment);
  std::sort(segs.begin(), segs.end());
  out.segments_used = static_cast<std::size_t>(std::unique(segs.begin(), segs.end()) - segs.begin());
  out.points_used = kept.size();
  out.degenerate = e.degenerate;
  out.corrected = x;
  out.valid = true;
  out.iterations = 1;
  return out;
}

IteratedCorrection iterated_point_to_line(const laser::SegmentMatcher& matcher, const Scan& scan,
                                          const LineMap& map, const Pose2& estimate,
                                          const IteratedCorrectionOptions& options) {
  validate(options);
  if (!std::isfinite(estimate.x) || !std::isfinite(estimate.y) ||
      !std::isfinite(estimate.theta)) {
    throw UsageError("iterated_point_to_line: the estimate is not finite");
  }
  IteratedCorrection out;
  out.corrected = estimate;
  Pose2 pose = estimate;
  for (int it = 0; it < options.max_iterations; ++it) {
    laser::MatchResult m = matcher.match(scan, map, pose);
    IteratedCorrection step = solve_point_to_line(m.matches, map, pose, options);
    if (!step.valid) {
      out.iterations = it + 1;
      return out;  // not valid: corrected = estimate
    }
    const double dt = std::hypot(step.corrected.x - pose.x, step.corrected.y - pose.y);
    const double dth = std::abs(angle_diff(step.corrected.theta, pose.theta));
    pose = step.corrected;
    step.matches = std::move(m.matches);
    step.iterations = it + 1;
    out = std::move(step);
    if (dt < options.translation_tolerance && dth < options.rotation_tolerance) {
      out.converged = true;
      break;
    }
  }
  return out;
}

}  // namespace locbench::pose_correction
