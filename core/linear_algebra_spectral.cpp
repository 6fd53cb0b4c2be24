// The SVD and the symmetric eigen-decompositions of core/linear_algebra.h, in a unit of their own
// (compiled apart from the unity batches, as is linear_algebra.cpp): with the
// factorisations (linear_algebra.cpp) they take about 40 s of compile CPU at -O1, which two units
// share between the cores.
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "core/linear_algebra.h"

namespace locbench::linalg {

Svd jacobi_svd(const Eigen::MatrixXd& a, unsigned int options) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, options);
  Svd out;
  out.singular_values = svd.singularValues();
  if (svd.computeU()) out.u = svd.matrixU();
  if (svd.computeV()) out.v = svd.matrixV();
  return out;
}

SymmetricEigen2 symmetric_eigen2(const Eigen::Matrix2d& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(a);
  return {es.eigenvalues(), es.eigenvectors()};
}

SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
  return {es.eigenvalues(), es.eigenvectors()};
}

}  // namespace locbench::linalg
