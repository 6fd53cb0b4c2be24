#pragma once
// The solver side of calibrate_ml (ml_calibration.h): the weighted least-squares problem
// Σ‖Σᵢ⁻¹ᐟ² rᵢ‖² over the free calibration parameters on Ceres Solver — whitened residuals with
// their exact Jacobian, Levenberg–Marquardt, the whitened Jacobian for the Fisher information,
// and the restriction to the directions the data determine. ML_CALIBRATION.md, sections 3 and 8.
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/calibration_model.h"

namespace ceres {
class Problem;
}

namespace locbench::calibration::ml_solver {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// The free parameters of one solve: which of the six, over which samples.
struct Problem {
  const CalibrationData& data;
  std::vector<std::size_t> active;  // sample indices
  std::vector<int> free;            // indices into the 6-vector
  Vector6 base;                     // values of all six (fixed ones stay)

  Vector6 full(const Eigen::VectorXd& x) const {
    Vector6 v = base;
    for (std::size_t j = 0; j < free.size(); ++j) v(free[j]) = x(static_cast<Eigen::Index>(j));
    return v;
  }
  Eigen::VectorXd free_values(const Vector6& v) const {
    Eigen::VectorXd x(static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j) x(static_cast<Eigen::Index>(j)) = v(free[j]);
    return x;
  }
  // Raw residuals predicted − reference, 3 per active sample.
  Eigen::VectorXd residuals(const Vector6& v) const {
    const ModelParameters p = ModelParameters::from_vector(v);
    Eigen::VectorXd r(3 * static_cast<Eigen::Index>(active.size()));
    for (std::size_t i = 0; i < active.size(); ++i) {
      r.segment<3>(3 * static_cast<Eigen::Index>(i)) = reference_residual(data, data.samples[active[i]], p);
    }
    return r;
  }
};

// Per active sample: Σᵢ⁻¹ᐟ² (inverse Cholesky factor) to whiten its residual.
using Whitening = std::vector<Eigen::Matrix3d>;

// The Ceres problem Σ‖Σᵢ⁻¹ᐟ² rᵢ‖² over the free parameters `x` (one parameter block, which
// Ceres reads and writes in place: `x` must outlive the problem). `w` is read at every
// evaluation, so the noise alternation may replace its matrices between solves.
std::unique_ptr<ceres::Problem> whitened_problem(const Problem& pb, const Whitening& w, Eigen::VectorXd& x);

// Whitened Jacobian (3 rows per active sample) at the parameter block's current values.
Eigen::MatrixXd whitened_jacobian(ceres::Problem& problem, Eigen::Index rows, Eigen::Index cols);

// Restricts the parameter block to the directions the data determine at its current values
// (undetermined combinations then keep those values through the next solve).
void restrict_to_determined(ceres::Problem& problem, Eigen::VectorXd& x);

struct LmOutcome {
  int iterations = 0;
  bool converged = false;
};

// Levenberg–Marquardt from the parameter block's current values.
LmOutcome levenberg_marquardt(ceres::Problem& problem, Eigen::VectorXd& x, int max_iterations);

}  // namespace locbench::calibration::ml_solver
