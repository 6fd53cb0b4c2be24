#include "algorithms/calibration/identifiability.h"

#include <fmt/format.h>
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/linear_algebra.h"

namespace locbench::calibration {

IdentifiabilityReport analyze_identifiability(const Eigen::MatrixXd& jacobian,
                                              const Eigen::MatrixXd& measurement_covariance,
                                              const std::vector<std::string>& names, const Eigen::VectorXd& values,
                                              double relative_tolerance) {
  const Eigen::Index p = jacobian.cols();
  if (static_cast<Eigen::Index>(names.size()) != p || values.size() != p ||
      measurement_covariance.rows() != jacobian.rows() || measurement_covariance.cols() != jacobian.rows()) {
    throw std::invalid_argument("analyze_identifiability: dimensions do not match");
  }
  // Whitened Jacobian L⁻¹J: F = (L⁻¹J)ᵀ(L⁻¹J); its singular values are √eig(F).
  Eigen::MatrixXd W;
  if (!linalg::cholesky_lower_solve(measurement_covariance, jacobian, W)) {
    throw std::invalid_argument("analyze_identifiability: covariance not positive definite");
  }
  linalg::Svd svd = linalg::jacobi_svd(W, Eigen::ComputeFullV);
  const Eigen::VectorXd s = std::move(svd.singular_values);  // descending
  const Eigen::MatrixXd V = std::move(svd.v);

  IdentifiabilityReport r;
  r.parameter_count = static_cast<int>(p);
  const double smax = s.size() > 0 ? s(0) : 0.0;
  // Eigenvalues of F are s²; compare them (not s) with the tolerance.
  const double cutoff = relative_tolerance * smax * smax;
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(p, p);
  std::vector<Eigen::VectorXd> null_dirs;
  for (Eigen::Index i = 0; i < p; ++i) {
    const double lambda = i < s.size() ? s(i) * s(i) : 0.0;
    if (lambda > cutoff && lambda > 0.0) {
      ++r.rank;
      cov += V.col(i) * V.col(i).transpose() / lambda;
    } else {
      null_dirs.push_back(V.col(i));
    }
  }
  r.covariance = cov;
  r.condition_number = r.rank == r.parameter_count && r.rank > 0 ? (smax * smax) / (s(r.rank - 1) * s(r.rank - 1))
                                                                 : std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& d : null_dirs) {
    std::string text;
    for (Eigen::Index j = 0; j < p; ++j) {
      if (std::abs(d(j)) < 1e-6) continue;
      text += fmt::format("{}{:+.3f}·{}", text.empty() ? "" : " ", d(j), names[j]);
    }
    r.undetermined_combinations.push_back(text);
  }
  for (Eigen::Index j = 0; j < p; ++j) {
    ParameterFinding f;
    f.name = names[j];
    f.value = values(j);
    for (std::size_t k = 0; k < null_dirs.size(); ++k) {
      if (std::abs(null_dirs[k](j)) > 1e-6) {
        f.identifiable = false;
        f.reason = "the measurements do not change along " + r.undetermined_combinations[k];
        break;
      }
    }
    f.standard_error = f.identifiable ? std::sqrt(cov(j, j)) : std::numeric_limits<double>::infinity();
    r.parameters.push_back(std::move(f));
  }
  return r;
}

}  // namespace locbench::calibration
