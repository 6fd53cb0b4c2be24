#pragma once
// Maximum-likelihood fitting of a few parameters: minimises a negative log-likelihood by a
// damped Newton method with the exact gradient and Hessian when the caller gives them, a
// central-difference gradient and Hessian otherwise, and gives each parameter
// a Wald 95% interval from the observed Fisher information (the Hessian at the optimum).
// Parameters that must stay positive are fitted on a log scale and their intervals mapped back.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace locbench::diagnosis {

struct FitParameter {
  std::string name;
  double initial = 0.0;
  double scale = 1.0;     // a typical size of a change (sets finite-difference steps)
  bool positive = false;  // fitted as log(value)
};

struct FitResult {
  std::vector<std::string> names;  // filled by callers that need to find a coordinate by name
  std::vector<double> values;
  std::vector<double> ci_low, ci_high;  // Wald 95% (on the log scale for positive parameters)
  std::vector<double> standard_errors;  // of the fitted coordinate (log for positive ones)
  Eigen::MatrixXd covariance;           // of the fitted coordinates (inverse Hessian)
  double nll = 0.0;                     // at the optimum
  int iterations = 0;
  bool converged = false;
  bool hessian_ok = true;            // positive definite at the optimum
  double max_abs_correlation = 0.0;  // between any two fitted coordinates
  int most_correlated_a = -1, most_correlated_b = -1;
};

using NegLogLikelihood = std::function<double(const std::vector<double>& values)>;

// The exact gradient and Hessian of the NLL with respect to the values (not their log scale) at
// `values`; false when they cannot be given there (central differences are then used).
using NllDerivatives =
    std::function<bool(const std::vector<double>& values, Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian)>;

// `nll` may return +inf for invalid values (the step is then shortened).
FitResult fit_max_likelihood(const NegLogLikelihood& nll, const std::vector<FitParameter>& params,
                             int max_iterations = 100, const NllDerivatives& derivatives = {});

// Stores `fit` in a channel's fit result (members fit, model, nll) with the model `apply` makes of
// the fitted values and the NLL there.
template <class ChannelFit, class Apply>
void adopt_fit(ChannelFit& out, FitResult fit, const Apply& apply) {
  out.fit = std::move(fit);
  out.model = apply(out.fit.values);
  out.nll = out.fit.nll;
}

}  // namespace locbench::diagnosis
