#include "core/pose_observability.h"

#include <Eigen/Eigenvalues>

namespace locbench {

PoseObservability pose_observability(const Eigen::Matrix3d& h, double length, double ratio) {
  PoseObservability o;
  o.scale = Eigen::Vector3d(1.0, 1.0, 1.0 / length).asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(o.scale * h * o.scale);
  o.values = es.eigenvalues();
  o.vectors = es.eigenvectors();
  const double largest = o.values.maxCoeff();
  for (std::size_t k = 0; k < 3; ++k) {
    o.observable[k] = largest > 0.0 && o.values[static_cast<Eigen::Index>(k)] > ratio * largest;
    o.degenerate = o.degenerate || !o.observable[k];
  }
  return o;
}

}  // namespace locbench
