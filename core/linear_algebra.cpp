#include "core/linear_algebra.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

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

Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& a) { return a.completeOrthogonalDecomposition().pseudoInverse(); }

Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& a) { return a.completeOrthogonalDecomposition().pseudoInverse(); }

LdltSolve ldlt_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  LdltSolve out;
  out.x = ldlt.solve(b);
  out.ok = ldlt.info() == Eigen::Success;
  out.positive = ldlt.isPositive();
  return out;
}

bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out) {
  const Eigen::LLT<Eigen::MatrixXd> llt(a);
  if (llt.info() != Eigen::Success) return false;
  out = llt.matrixL().solve(b);
  return true;
}

bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& out) {
  const Eigen::LLT<Eigen::MatrixXd> llt(a);
  if (llt.info() != Eigen::Success) return false;
  out = llt.matrixL().solve(b);
  return true;
}

Eigen::MatrixXd inverse(const Eigen::MatrixXd& a) { return a.inverse(); }

}  // namespace locbench::linalg
