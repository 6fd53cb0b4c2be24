#include "algorithms/diagnosis/ml_fit.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/linear_algebra.h"

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

// The NLL over the fitted coordinates z (log scale for positive parameters) with its gradient and
// Hessian: exact where the caller gives derivatives, central differences elsewhere.
class Surface {
 public:
  Surface(const NegLogLikelihood& nll, const std::vector<FitParameter>& params, const NllDerivatives& derivatives)
      : nll_(nll), params_(params), derivatives_(derivatives), coords_{params}, n_(params.size()) {}

  double operator()(const Eigen::VectorXd& x) const {
    const double v = nll_(coords_.values(x));
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  }

  // The last point's derivatives: a fit that stops because no damped step descends, and a restart
  // from where the last one stopped, ask again at the same point.
  void gradient_hessian(const Eigen::VectorXd& x, double fx, Eigen::VectorXd& g, Eigen::MatrixXd& h) {
    if (last_x_.size() == x.size() && last_x_ == x) {
      g = last_g_;
      h = last_h_;
      return;
    }
    compute_gradient_hessian(x, fx, g, h, true);
    last_x_ = x;
    last_g_ = g;
    last_h_ = h;
  }

  // The Hessian for the intervals: exact wherever the caller gives derivatives, also for the
  // parameters the descent differences (FitParameter::differences).
  Eigen::MatrixXd interval_hessian(const Eigen::VectorXd& x, double fx) {
    Eigen::VectorXd g;
    Eigen::MatrixXd h;
    const bool marked =
        std::any_of(params_.begin(), params_.end(), [](const FitParameter& p) { return p.differences; });
    if (marked && derivatives_) {
      compute_gradient_hessian(x, fx, g, h, false);
    } else {
      gradient_hessian(x, fx, g, h);
    }
    return h;
  }

  const Coordinates& coords() const { return coords_; }

 private:
  // Exact derivatives with respect to the values, mapped to the fitted coordinates z (v = e^z
  // for positive parameters: ∂f/∂z = v·∂f/∂v, ∂²f/∂z_i∂z_j = v_i·v_j·∂²f/∂v_i∂v_j + δ_ij·v_i·∂f/∂v_i).
  bool exact(const Eigen::VectorXd& x, const std::vector<bool>& skipped, Eigen::VectorXd& g, Eigen::MatrixXd& h) const {
    if (!derivatives_) return false;
    const std::vector<double> v = coords_.values(x);
    if (!derivatives_(v, skipped, g, h) || !g.allFinite() || !h.allFinite()) return false;
    for (std::size_t i = 0; i < n_; ++i) {
      if (!params_[i].positive) continue;
      h.row(i) *= v[i];
      h.col(i) *= v[i];
      h(i, i) += v[i] * g[i];
      g[i] *= v[i];
    }
    return true;
  }

  // Central differences for every coordinate without exact derivatives, and for the rows and
  // columns of those marked `differences` when there are and `marked_differences` is set.
  void compute_gradient_hessian(const Eigen::VectorXd& x, double fx, Eigen::VectorXd& g, Eigen::MatrixXd& h,
                                bool marked_differences) const {
    const auto& f = *this;
    const std::size_t n = n_;
    std::vector<bool> skipped(n, false);
    for (std::size_t i = 0; i < n && marked_differences; ++i) skipped[i] = params_[i].differences;
    const bool have_exact = exact(x, skipped, g, h);
    if (!have_exact) {
      g.resize(n);
      h.resize(n, n);
    }
    auto differenced = [&](std::size_t i) { return !have_exact || skipped[i]; };
    std::vector<double> fp(n), fm(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!differenced(i)) continue;
      Eigen::VectorXd a = x, b = x;
      a[i] += coords_.step(i);
      b[i] -= coords_.step(i);
      fp[i] = f(a);
      fm[i] = f(b);
      g[i] = (fp[i] - fm[i]) / (2.0 * coords_.step(i));
      h(i, i) = (fp[i] - 2.0 * fx + fm[i]) / (coords_.step(i) * coords_.step(i));
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!differenced(i) && !differenced(j)) continue;
        Eigen::VectorXd pp = x, pm = x, mp = x, mm = x;
        pp[i] += coords_.step(i), pp[j] += coords_.step(j);
        pm[i] += coords_.step(i), pm[j] -= coords_.step(j);
        mp[i] -= coords_.step(i), mp[j] += coords_.step(j);
        mm[i] -= coords_.step(i), mm[j] -= coords_.step(j);
        h(i, j) = h(j, i) = (f(pp) - f(pm) - f(mp) + f(mm)) / (4.0 * coords_.step(i) * coords_.step(j));
      }
    }
  }

  const NegLogLikelihood& nll_;
  const std::vector<FitParameter>& params_;
  const NllDerivatives& derivatives_;
  const Coordinates coords_;
  const std::size_t n_;
  Eigen::VectorXd last_x_;
  Eigen::VectorXd last_g_;
  Eigen::MatrixXd last_h_;
};

// Where the descent stands: the point, its NLL, the damping.
struct Descent {
  Eigen::VectorXd z;
  double fx = 0.0;
  double lambda = 1e-3;
};

// One Newton iteration: Levenberg damping on the scaled diagonal, raised until the step lowers
// the NLL (at most 30 tries). Returns whether it did; sets `converged` when an (almost) undamped
// step gains next to nothing (relative 1e-9).
bool damped_newton_step(const Surface& f, const Eigen::VectorXd& g, const Eigen::MatrixXd& h, Descent& d,
                        bool& converged) {
  const std::size_t n = static_cast<std::size_t>(g.size());
  for (int tries = 0; tries < 30; ++tries) {
    Eigen::MatrixXd a = h;
    for (std::size_t i = 0; i < n; ++i) a(i, i) += d.lambda * std::max(std::abs(h(i, i)), 1e-12);
    const linalg::LdltSolve solved = linalg::ldlt_solve(a, g);
    const Eigen::VectorXd dz = -solved.x;
    if (!solved.ok || !dz.allFinite() || !solved.positive) {
      d.lambda *= 10.0;
      continue;
    }
    const Eigen::VectorXd zn = d.z + dz;
    // A step below the resolution of z (strong damping) leaves z as it is, and f(z) = fx.
    const double fn = zn == d.z ? d.fx : f(zn);
    if (fn < d.fx) {
      const double gain = d.fx - fn;
      d.z = zn;
      d.fx = fn;
      if (gain < 1e-9 * (1.0 + std::abs(d.fx)) && d.lambda <= 1e-2) converged = true;
      d.lambda = std::max(d.lambda / 10.0, 1e-9);
      return true;
    }
    d.lambda *= 10.0;
  }
  return false;
}

// Damped Newton from `d`, restarted (damping reset) until a restart gains nothing: a damped step
// that stalls far from the optimum would otherwise inflate the likelihood-ratio statistics
// computed against it.
void descend(Surface& f, Descent& d, int max_iterations, FitResult& r) {
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  for (int restart = 0; restart < 4 && d.z.size() > 0; ++restart) {
    const double before_restart = d.fx;
    d.lambda = 1e-3;
    r.converged = false;
    for (int it = 0; it < max_iterations; ++it, ++r.iterations) {
      f.gradient_hessian(d.z, d.fx, g, h);
      if (!damped_newton_step(f, g, h, d, r.converged)) {
        r.converged = true;  // no descent step exists at this resolution: a (local) minimum
        break;
      }
      if (r.converged) break;
    }
    if (before_restart - d.fx < 1e-9 * (1.0 + std::abs(d.fx))) break;
  }
}

// Standard errors, 95% intervals and correlations from the Hessian at the optimum z.
void fill_intervals(Surface& f, const Eigen::VectorXd& z, double fx, const std::vector<FitParameter>& params,
                    FitResult& r) {
  const std::size_t n = params.size();
  const Eigen::MatrixXd h = f.interval_hessian(z, fx);
  const linalg::SymmetricEigen eig = linalg::symmetric_eigen(Eigen::MatrixXd(0.5 * (h + h.transpose())));
  r.hessian_ok = eig.values.minCoeff() > 1e-12 * std::max(1.0, eig.values.maxCoeff());
  if (r.hessian_ok) {
    r.covariance = eig.vectors * eig.values.cwiseInverse().asDiagonal() * eig.vectors.transpose();
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double se =
        r.hessian_ok ? std::sqrt(std::max(r.covariance(i, i), 0.0)) : std::numeric_limits<double>::infinity();
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
}

}  // namespace

FitResult fit_max_likelihood(const NegLogLikelihood& nll, const std::vector<FitParameter>& params, int max_iterations,
                             const NllDerivatives& derivatives) {
  const std::size_t n = params.size();
  Surface f(nll, params, derivatives);
  Descent d;
  d.z.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    d.z[i] = params[i].positive ? std::log(std::max(params[i].initial, 1e-300)) : params[i].initial;
  }
  d.fx = f(d.z);
  FitResult r;
  descend(f, d, max_iterations, r);
  r.nll = d.fx;
  r.values = f.coords().values(d.z);
  r.ci_low.assign(n, 0.0);
  r.ci_high.assign(n, 0.0);
  r.standard_errors.assign(n, std::numeric_limits<double>::infinity());
  r.covariance = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return r;
  fill_intervals(f, d.z, d.fx, params, r);
  return r;
}

}  // namespace locbench::diagnosis
