#pragma once
// Which directions of a planar pose (x, y, θ) a Gauss–Newton system determines: the
// eigen-decomposition of its 3×3 normal matrix H in units where θ is scaled by a length (so the
// eigenvalues compare like with like). Shared by the thesis's iterated point-to-line correction
// and the PL-ICP baseline.
#include <Eigen/Core>
#include <array>

namespace locbench {

struct PoseObservability {
  Eigen::Matrix3d scale;                             // diag(1, 1, 1/length): δ = scale · δ'
  Eigen::Vector3d values;                            // eigenvalues of scale · H · scale, ascending
  Eigen::Matrix3d vectors;                           // their eigenvectors (columns)
  std::array<bool, 3> observable{true, true, true};  // value > ratio × the largest value
  bool degenerate = false;                           // some direction is not observable
};

// `length` [m] > 0 scales θ; `ratio` in [0, 1) is the eigenvalue ratio of a degenerate
// direction.
PoseObservability pose_observability(const Eigen::Matrix3d& h, double length, double ratio);

}  // namespace locbench
