#include "algorithms/diagnosis/ml_fit.h"

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace locbench::diagnosis {
namespace {

struct Coordinates {
  const std::vector<FitParameter>& p;
  std::vector<double> values(const Eigen::VectorXd& z) const {
    std::vector<double> v(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) v[i] = p[i].positive ? std::exp(z[i]) : z[i];
    return v;
  }
  double step(std::size_t i) const { return p[i].positive ? 1e-4 : 1e-4 * p[i].scale; }
};

// Central-difference gradient and Hessian of f at x (2n + 2n(n−1) + 1 evaluations).
template <typename F>
void gradient_hessian(const F& f, const Coordinates& coords, const Eigen::VectorXd& x, double fx,
                      Eigen::VectorXd& g, Eigen::MatrixXd& h) {
  const auto n = static_cast<std::size_t>(x.size());
  g.resize(x.size());
  h.resize(x.size(), x.size());
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::VectorXd a = x, b = x;
    a[i] += coords.step(i);
    b[i] -= coords.step(i);
    const double fp = f(a), fm = f(b);
    g[i] = (fp - fm) / (2.0 * coords.step(i));
    h(i, i) = (fp - 2.0 * fx + fm) / (coords.step(i) * coords.step(i));
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      Eigen::VectorXd pp = x, pm = x, mp = x, mm = x;
      pp[i] += coords.step(i), pp[j] += coords.step(j);
      pm[i] += coords.step(i), pm[j] -= coords.step(j);
      mp[i] -= coords.step(i), mp[j] += coords.step(j);
      mm[i] -= coords.step(i), mm[j] -= coords.step(j);
      h(i, j) = h(j, i) = (f(pp) - f(pm) - f(mp) + f(mm)) / (4.0 * coords.step(i) * coords.step(j));
    }
  }
}

// The NLL in the fitted coordinates for Ceres, with its central-difference gradient (steps as
// for the Hessian). A non-finite value or gradient reports failure: Ceres's line search then
// shortens the step.
class NllFunction final : public ceres::FirstOrderFunction {
 public:
  NllFunction(const std::function<double(const Eigen::VectorXd&)>& f, const Coordinates& coords,
              int n)
      : f_(f), coords_(coords), n_(n) {}
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(parameters, n_);
    *cost = f_(x);
    if (!std::isfinite(*cost)) return false;
    if (gradient == nullptr) return true;
    for (int i = 0; i < n_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      Eigen::VectorXd a = x, b = x;
      a[i] += coords_.step(k);
      b[i] -= coords_.step(k);
      gradient[i] = (f_(a) - f_(b)) / (2.0 * coords_.step(k));
      if (!std::isfinite(gradient[i])) return false;
    }
    return true;
  }
  int NumParameters() const override { return n_; }

 private:
  const std::function<double(const Eigen::VectorXd&)>& f_;
  const Coordinates& coords_;
  int n_;
};

}  // namespace

FitResult fit_max_likelihood(const NegLogLikelihood& nll, const std::vector<FitParameter>& params,
                             int max_iterations) {
  const std::size_t n = params.size();
  const Coordinates coords{params};
  Eigen::VectorXd z(n);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = params[i].positive ? std::log(std::max(params[i].initial, 1e-300)) : params[i].initial;
  }
  const std::function<double(const Eigen::VectorXd&)> f = [&](const Eigen::VectorXd& x) {
    const double v = nll(coords.values(x));
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  };

  FitResult r;
  double fx = f(z);
  // Ceres's BFGS line search on the NLL (a general likelihood, not a sum of squares), restarted
  // (fresh Hessian approximation) until a restart gains nothing: a search that stalls far from
  // the optimum would otherwise inflate the likelihood-ratio statistics computed against it.
  // `max_iterations` counts Newton-sized steps; BFGS gets 10 line-search iterations for each.
  if (n > 0 && std::isfinite(fx)) {
    ceres::GradientProblem problem(new NllFunction(f, coords, static_cast<int>(n)));
    ceres::GradientProblemSolver::Options o;
    o.line_search_direction_type = ceres::BFGS;
    o.max_num_iterations = 10 * max_iterations;
    o.function_tolerance = 1e-12;
    o.gradient_tolerance = 1e-10;
    o.parameter_tolerance = 1e-12;
    o.logging_type = ceres::SILENT;
    o.minimizer_progress_to_stdout = false;
    for (int restart = 0; restart < 4; ++restart) {
      const double before_restart = fx;
      ceres::GradientProblemSolver::Summary summary;
      ceres::Solve(o, problem, z.data(), &summary);
      r.iterations += std::max(0, static_cast<int>(summary.iterations.size()) - 1);
      fx = f(z);
      // CONVERGENCE, or a line search that finds no descent at the differences' resolution.
      r.converged = summary.termination_type == ceres::CONVERGENCE ||
                    summary.termination_type == ceres::FAILURE;
      if (before_restart - fx < 1e-9 * (1.0 + std::abs(fx))) break;
    }
  } else {
    r.converged = n == 0;
  }
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  r.nll = fx;
  r.values = coords.values(z);
  r.ci_low.assign(n, 0.0);
  r.ci_high.assign(n, 0.0);
  r.standard_errors.assign(n, std::numeric_limits<double>::infinity());
  r.covariance = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return r;
  gradient_hessian(f, coords, z, fx, g, h);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (h + h.transpose()));
  r.hessian_ok = eig.eigenvalues().minCoeff() > 1e-12 * std::max(1.0, eig.eigenvalues().maxCoeff());
  if (r.hessian_ok) {
    r.covariance = eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() *
                   eig.eigenvectors().transpose();
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double se = r.hessian_ok ? std::sqrt(std::max(r.covariance(i, i), 0.0))
                                   : std::numeric_limits<double>::infinity();
    r.standard_errors[i] = se;
    const double lo = z[i] - 1.959963984540054 * se, hi = z[i] + 1.959963984540054 * se;
    r.ci_low[i] = params[i].positive ? std::exp(lo) : lo;
    r.ci_high[i] = params[i].positive ? std::exp(hi) : hi;
    for (std::size_t j = i + 1; j < n && r.hessian_ok; ++j) {
      const double c = r.covariance(i, j) / std::sqrt(r.covariance(i, i) * r.covariance(j, j));
      if (std::abs(c) > r.max_abs_correlation) {
        r.max_abs_correlation = std::abs(c);
        r.most_correlated_a = static_cast<int>(i);
        r.most_correlated_b = static_cast<int>(j);
      }
    }
  }
  if (!r.hessian_ok) r.max_abs_correlation = 1.0;
  return r;
}


}  // namespace locbench::diagnosis
