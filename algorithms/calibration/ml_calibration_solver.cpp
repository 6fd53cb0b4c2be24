#include "algorithms/calibration/ml_calibration_solver.h"

#include <ceres/cost_function.h>
#include <ceres/crs_matrix.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>

#include "core/linear_algebra.h"

namespace locbench::calibration::ml_solver {

namespace {

// One sample's whitened residual Σᵢ⁻¹ᐟ² rᵢ and its exact Jacobian Σᵢ⁻¹ᐟ² ∂rᵢ/∂x over the free
// parameters x (reference_residual_with_jacobian), for Ceres. `whitening` is shared by every
// sample's cost and replaced between the noise alternation's rounds.
class WhitenedResidual final : public ceres::CostFunction {
 public:
  WhitenedResidual(const Problem& pb, const Whitening& whitening, std::size_t slot)
      : pb_(pb), whitening_(whitening), slot_(slot) {
    set_num_residuals(3);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(pb.free.size()));
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    Vector6 v = pb_.base;
    const std::size_t n = pb_.free.size();
    for (std::size_t j = 0; j < n; ++j) v(pb_.free[j]) = x[0][j];
    const CalibrationSample& sample = pb_.data.samples[pb_.active[slot_]];
    const ModelParameters p = ModelParameters::from_vector(v);
    const Eigen::Matrix3d& w = whitening_[slot_];
    // Plain loops: Eigen's small products are slow in the unoptimised test build.
    const double* wd = w.data();  // column-major: w(i, k) = wd[i + 3k]
    double r[3] = {0.0, 0.0, 0.0};
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      const ResidualWithJacobian rj = reference_residual_with_jacobian(pb_.data, sample, p);
      const double* rd = rj.residual.data();
      const double* jd = rj.jacobian.data();  // column-major: J(k, c) = jd[k + 3c]
      for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t k = 0; k < 3; ++k) r[row] += wd[row + 3 * k] * rd[k];
        for (std::size_t j = 0; j < n; ++j) {
          const auto col = static_cast<std::size_t>(pb_.free[j]);
          double sum = 0.0;
          for (std::size_t k = 0; k < 3; ++k) sum += wd[row + 3 * k] * jd[k + 3 * col];
          jacobians[0][row * n + j] = sum;
        }
      }
    } else {
      const Eigen::Vector3d raw = reference_residual(pb_.data, sample, p);
      const double* rd = raw.data();
      for (std::size_t row = 0; row < 3; ++row) {
        for (std::size_t k = 0; k < 3; ++k) r[row] += wd[row + 3 * k] * rd[k];
      }
    }
    bool finite = true;
    for (std::size_t c = 0; c < 3; ++c) {
      residuals[c] = r[c];
      finite = finite && std::isfinite(r[c]);
    }
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (std::size_t i = 0; i < 3 * n; ++i) finite = finite && std::isfinite(jacobians[0][i]);
    }
    return finite;
  }

 private:
  const Problem& pb_;
  const Whitening& whitening_;
  std::size_t slot_;  // index into pb.active and whitening
};

}  // namespace

// The Ceres problem Σ‖Σᵢ⁻¹ᐟ² rᵢ‖² over the free parameters `x` (one parameter block).
std::unique_ptr<ceres::Problem> whitened_problem(const Problem& pb, const Whitening& w, Eigen::VectorXd& x) {
  ceres::Problem::Options po;
  auto problem = std::make_unique<ceres::Problem>(po);
  for (std::size_t i = 0; i < pb.active.size(); ++i) {
    problem->AddResidualBlock(new WhitenedResidual(pb, w, i), nullptr, x.data());
  }
  return problem;
}

// Whitened Jacobian (3 rows per active sample) at x, from the Ceres problem.
Eigen::MatrixXd whitened_jacobian(ceres::Problem& problem, Eigen::Index rows, Eigen::Index cols) {
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[static_cast<std::size_t>(r)]; k < crs.rows[static_cast<std::size_t>(r) + 1]; ++k) {
      J(r, crs.cols[static_cast<std::size_t>(k)]) = crs.values[static_cast<std::size_t>(k)];
    }
  }
  return J;
}

// Ceres's Levenberg–Marquardt (dense QR) on Σ‖Σᵢ⁻¹ᐟ² rᵢ‖². Tolerances: relative cost change
// 1e-10 (χ² ≈ 3n/2 moves by < 1e-6 per thousand samples: far below one standard error²) and
// step 1e-10 of |x| (ML_CALIBRATION.md compares it with the hand-written solver it replaced).
LmOutcome levenberg_marquardt(ceres::Problem& problem, Eigen::VectorXd& x, int max_iterations) {
  LmOutcome out;
  if (x.size() == 0) {
    out.converged = true;
    return out;
  }
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = max_iterations;
  o.function_tolerance = 1e-10;
  o.parameter_tolerance = 1e-10;
  o.gradient_tolerance = 1e-10;
  o.num_threads = 1;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  out.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  return out;
}

namespace {

// x = x₀ + B·u: the solver steps only within the span of B's columns.
class LinearSubspace final : public ceres::Manifold {
 public:
  explicit LinearSubspace(Eigen::MatrixXd basis) : basis_(std::move(basis)), inverse_(linalg::pseudo_inverse(basis_)) {}
  int AmbientSize() const override { return static_cast<int>(basis_.rows()); }
  int TangentSize() const override { return static_cast<int>(basis_.cols()); }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    Eigen::Map<Eigen::VectorXd>(x_plus_delta, basis_.rows()) =
        Eigen::Map<const Eigen::VectorXd>(x, basis_.rows()) +
        basis_ * Eigen::Map<const Eigen::VectorXd>(delta, basis_.cols());
    return true;
  }
  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    RowMajor(jacobian, basis_.rows(), basis_.cols()) = basis_;
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<Eigen::VectorXd>(y_minus_x, basis_.cols()) =
        inverse_ *
        (Eigen::Map<const Eigen::VectorXd>(y, basis_.rows()) - Eigen::Map<const Eigen::VectorXd>(x, basis_.rows()));
    return true;
  }
  bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
    RowMajor(jacobian, basis_.cols(), basis_.rows()) = inverse_;
    return true;
  }

 private:
  using RowMajor = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
  Eigen::MatrixXd basis_, inverse_;
};

}  // namespace

// Ceres's damping lets Levenberg–Marquardt step along directions the data do not determine (a
// straight run's wheelbase moved 3 % along its flat direction). Before each solve, the
// parameter block is restricted to the directions the data determine at its start, so the
// undetermined combinations keep their start (closed-form) values: in Marquardt-scaled
// coordinates (D = diag(JᵀJ)^−½), the eigenvectors of D·JᵀJ·D with at least 1e-8 of the largest
// eigenvalue (exact derivatives leave rounding, ~1e-16, in an exactly flat direction; central
// differences, used before, left ~1e-10). Identifiable
// problems solve on the full space.
void restrict_to_determined(ceres::Problem& problem, Eigen::VectorXd& x) {
  problem.SetManifold(x.data(), nullptr);
  const auto rows = 3 * static_cast<Eigen::Index>(problem.NumResidualBlocks());
  const Eigen::MatrixXd J = whitened_jacobian(problem, rows, x.size());
  const Eigen::MatrixXd H = J.transpose() * J;
  const Eigen::VectorXd d = H.diagonal().cwiseMax(1e-12 * H.diagonal().maxCoeff() + 1e-300).cwiseSqrt().cwiseInverse();
  const linalg::SymmetricEigen eig = linalg::symmetric_eigen(Eigen::MatrixXd(d.asDiagonal() * H * d.asDiagonal()));
  const double emax = eig.values.maxCoeff();
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    if (eig.values(k) > 1e-8 * emax) kept.push_back(k);
  }
  if (kept.size() == static_cast<std::size_t>(x.size())) return;
  if (kept.empty()) {
    problem.SetParameterBlockConstant(x.data());
    return;
  }
  Eigen::MatrixXd basis(x.size(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t c = 0; c < kept.size(); ++c) {
    basis.col(static_cast<Eigen::Index>(c)) = d.asDiagonal() * eig.vectors.col(kept[c]);
  }
  problem.SetManifold(x.data(), new LinearSubspace(basis));
}

}  // namespace locbench::calibration::ml_solver
