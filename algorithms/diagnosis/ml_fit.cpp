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

}  // namespace

FitResult fit_max_likelihood(const NegLogLikelihood& nll, const std::vector<FitParameter>& params, int max_iterations,
                             const NllDerivatives& derivatives) {
  const std::size_t n = params.size();
  const Coordinates coords{params};
  Eigen::VectorXd z(n);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = params[i].positive ? std::log(std::max(params[i].initial, 1e-300)) : params[i].initial;
  }
  auto f = [&](const Eigen::VectorXd& x) {
    const double v = nll(coords.values(x));
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  };
  // Exact derivatives with respect to the values, mapped to the fitted coordinates z (v = e^z
  // for positive parameters: ∂f/∂z = v·∂f/∂v, ∂²f/∂z_i∂z_j = v_i·v_j·∂²f/∂v_i∂v_j + δ_ij·v_i·∂f/∂v_i).
  auto exact = [&](const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& h) {
    if (!derivatives) return false;
    const std::vector<double> v = coords.values(x);
    if (!derivatives(v, g, h) || !g.allFinite() || !h.allFinite()) return false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!params[i].positive) continue;
      h.row(i) *= v[i];
      h.col(i) *= v[i];
      h(i, i) += v[i] * g[i];
      g[i] *= v[i];
    }
    return true;
  };
  // Central differences for every coordinate without exact derivatives, and for the rows and
  // columns of those marked `differences` when there are.
  auto compute_gradient_hessian = [&](const Eigen::VectorXd& x, double fx, Eigen::VectorXd& g, Eigen::MatrixXd& h) {
    const bool have_exact = exact(x, g, h);
    if (!have_exact) {
      g.resize(n);
      h.resize(n, n);
    }
    auto differenced = [&](std::size_t i) { return !have_exact || params[i].differences; };
    std::vector<double> fp(n), fm(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!differenced(i)) continue;
      Eigen::VectorXd a = x, b = x;
      a[i] += coords.step(i);
      b[i] -= coords.step(i);
      fp[i] = f(a);
      fm[i] = f(b);
      g[i] = (fp[i] - fm[i]) / (2.0 * coords.step(i));
      h(i, i) = (fp[i] - 2.0 * fx + fm[i]) / (coords.step(i) * coords.step(i));
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!differenced(i) && !differenced(j)) continue;
        Eigen::VectorXd pp = x, pm = x, mp = x, mm = x;
        pp[i] += coords.step(i), pp[j] += coords.step(j);
        pm[i] += coords.step(i), pm[j] -= coords.step(j);
        mp[i] -= coords.step(i), mp[j] += coords.step(j);
        mm[i] -= coords.step(i), mm[j] -= coords.step(j);
        h(i, j) = h(j, i) = (f(pp) - f(pm) - f(mp) + f(mm)) / (4.0 * coords.step(i) * coords.step(j));
      }
    }
  };

  // The last point's derivatives: a fit that stops because no damped step descends, and a restart
  // from where the last one stopped, ask again at the same point.
  Eigen::VectorXd last_x;
  Eigen::VectorXd last_g;
  Eigen::MatrixXd last_h;
  auto gradient_hessian = [&](const Eigen::VectorXd& x, double fx, Eigen::VectorXd& g, Eigen::MatrixXd& h) {
    if (last_x.size() == x.size() && last_x == x) {
      g = last_g;
      h = last_h;
      return;
    }
    compute_gradient_hessian(x, fx, g, h);
    last_x = x;
    last_g = g;
    last_h = h;
  };

  FitResult r;
  double fx = f(z);
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  double lambda = 1e-3;
  // Restarted (damping reset) until a restart gains nothing: a damped step that stalls far from
  // the optimum would otherwise inflate the likelihood-ratio statistics computed against it.
  for (int restart = 0; restart < 4 && n > 0; ++restart) {
    const double before_restart = fx;
    lambda = 1e-3;
    r.converged = false;
    for (int it = 0; it < max_iterations; ++it, ++r.iterations) {
      gradient_hessian(z, fx, g, h);
      // Levenberg damping on the scaled diagonal until the step lowers the NLL.
      bool improved = false;
      for (int tries = 0; tries < 30 && !improved; ++tries) {
        Eigen::MatrixXd a = h;
        for (std::size_t i = 0; i < n; ++i) a(i, i) += lambda * std::max(std::abs(h(i, i)), 1e-12);
        const linalg::LdltSolve solved = linalg::ldlt_solve(a, g);
        const Eigen::VectorXd dz = -solved.x;
        if (!solved.ok || !dz.allFinite() || !solved.positive) {
          lambda *= 10.0;
          continue;
        }
        const Eigen::VectorXd zn = z + dz;
        // A step below the resolution of z (strong damping) leaves z as it is, and f(z) = fx.
        const double fn = zn == z ? fx : f(zn);
        if (fn < fx) {
          const double gain = fx - fn;
          z = zn;
          fx = fn;
          // Converged when an (almost) undamped Newton step gains next to nothing (relative 1e-9).
          if (gain < 1e-9 * (1.0 + std::abs(fx)) && lambda <= 1e-2) r.converged = true;
          lambda = std::max(lambda / 10.0, 1e-9);
          improved = true;
        } else {
          lambda *= 10.0;
        }
      }
      if (!improved) {
        r.converged = true;  // no descent step exists at this resolution: a (local) minimum
        break;
      }
      if (r.converged) break;
    }
    if (before_restart - fx < 1e-9 * (1.0 + std::abs(fx))) break;
  }
  r.nll = fx;
  r.values = coords.values(z);
  r.ci_low.assign(n, 0.0);
  r.ci_high.assign(n, 0.0);
  r.standard_errors.assign(n, std::numeric_limits<double>::infinity());
  r.covariance = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::quiet_NaN());
  if (n == 0) return r;
  gradient_hessian(z, fx, g, h);
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
  return r;
}

}  // namespace locbench::diagnosis
