#pragma once
// The decompositions the numerical libraries use, behind plain functions so that their Eigen
// templates (JacobiSVD, SelfAdjointEigenSolver, CompleteOrthogonalDecomposition, LDLT, LLT,
// PartialPivLU) are instantiated once, in linear_algebra.cpp, instead of in every unit that uses
// them (at -O1 each costs a unit 2–10 s of compile CPU). Each function runs the very Eigen
// decomposition named in its comment, on the same matrix type, so results are the same bits as
// calling Eigen directly.
#include <Eigen/Core>

namespace locbench::linalg {

// Eigen::JacobiSVD<MatrixXd>(a, options): options are Eigen's ComputeThinU, ComputeFullV, ….
// U and V are empty when not asked for.
struct Svd {
  Eigen::VectorXd singular_values;  // descending
  Eigen::MatrixXd u;
  Eigen::MatrixXd v;
};
Svd jacobi_svd(const Eigen::MatrixXd& a, unsigned int options);

// Eigen::SelfAdjointEigenSolver of the matrix's lower triangle: eigenvalues ascending, the
// eigenvectors as columns in the same order.
struct SymmetricEigen2 {
  Eigen::Vector2d values;
  Eigen::Matrix2d vectors;
};
SymmetricEigen2 symmetric_eigen2(const Eigen::Matrix2d& a);
struct SymmetricEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& a);

// The Moore–Penrose pseudo-inverse by Eigen::CompleteOrthogonalDecomposition<MatrixXd> (the 3×3
// one too).
Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& a);
Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& a);

// Eigen::LDLT<MatrixXd>(a).solve(b); `ok` is info() == Success, `positive` isPositive().
struct LdltSolve {
  Eigen::VectorXd x;
  bool ok = false;
  bool positive = false;
};
LdltSolve ldlt_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

// L⁻¹b with L the lower Cholesky factor of a (Eigen::LLT<MatrixXd>); false when a is not
// positive definite (then `out` is untouched).
bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::VectorXd& out);
bool cholesky_lower_solve(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& out);
// The same for a 3×3 matrix (Eigen::LLT<Matrix3d>): no allocation, for per-step pose checks.
bool cholesky_lower_solve(const Eigen::Matrix3d& a, const Eigen::Vector3d& b, Eigen::Vector3d& out);

// a.inverse() of a dynamic-size matrix (Eigen: by PartialPivLU).
Eigen::MatrixXd inverse(const Eigen::MatrixXd& a);

}  // namespace locbench::linalg
