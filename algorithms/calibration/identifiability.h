#pragma once
// What a set of measurements can determine: the Fisher information F = Jᵀ Σ⁻¹ J of a
// measurement model at the estimate (J = ∂measurements/∂parameters), its rank and condition
// number, the standard error of each parameter, and the parameter combinations it leaves
// undetermined (the null space of F).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace locbench::calibration {

struct ParameterFinding {
  std::string name;
  double value = 0.0;
  double standard_error = 0.0;  // √(F⁺)ᵢᵢ; +∞ when not identifiable
  bool identifiable = true;
  std::string reason;  // why not (the undetermined combination), empty otherwise
};

struct IdentifiabilityReport {
  int rank = 0;
  int parameter_count = 0;
  double condition_number = 0.0;  // λ_max/λ_min of F; +∞ when rank-deficient
  std::vector<ParameterFinding> parameters;
  // Each undetermined direction as text, e.g. "+0.71·E_b −0.71·E_o".
  std::vector<std::string> undetermined_combinations;
  Eigen::MatrixXd covariance;  // F⁺ (pseudo-inverse), parameters in the order given
};

// `jacobian`: m×p; `measurement_covariance`: m×m, positive definite. A singular value of F
// below `relative_tolerance`·σ_max counts as zero. A parameter is identifiable when it has no
// component (above 1e-6) in any null-space direction.
IdentifiabilityReport analyze_identifiability(const Eigen::MatrixXd& jacobian,
                                              const Eigen::MatrixXd& measurement_covariance,
                                              const std::vector<std::string>& names, const Eigen::VectorXd& values,
                                              double relative_tolerance = 1e-10);

}  // namespace locbench::calibration
