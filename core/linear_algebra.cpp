#include "core/linear_algebra.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

namespace locbench::linalg {

Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& a) { return a.completeOrthogonalDecomposition().pseudoInverse(); }

// Through the dynamic-size decomposition: one instantiation of it (about 9 s of compile CPU each).
Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& a) { return pseudo_inverse(Eigen::MatrixXd(a)); }

LdltSolve ldlt_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
  LdltSolve out;
  out.x = ldlt.solve(b);
  out.ok = ldlt.info() == Eigen::Success;
  out.positive = ldlt.isPositive();
  return out;
}

namespace {

// L⁻¹b for the lower Cholesky factor L of a; false (out untouched) when a is not positive definite.
template <class Matrix, class Rhs>
bool lower_solve(const Matrix& a, const Rhs& b, Rhs& out) {
  const Eigen::LLT<Matrix> llt(a);
  if (llt.info() != Eigen::Success) return false;
  out = llt.matrixL().solve(b);
  return true;
}

}  // namespace

bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out) {
  return lower_solve(a, b, out);
}

bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& out) {
  return lower_solve(a, b, out);
}

bool cholesky_lower_solve(const Eigen::Matrix3d& a, const Eigen::Vector3d& b, Eigen::Vector3d& out) {
  return lower_solve(a, b, out);
}

Eigen::MatrixXd inverse(const Eigen::MatrixXd& a) { return a.inverse(); }

}  // namespace locbench::linalg
