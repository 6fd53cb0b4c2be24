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
    compute_gradient_hessian(x, fx, g, h);
    last_x_ = x;
    last_g_ = g;
    last_h_ = h;
  }

  const Coordinates& coords() const { return coords_; }

 private:
  // Exact derivatives with respect to the values, mapped to the fitted coordinates z (v = e^z
  // for positive parameters: ∂f/∂z = v·∂f/∂v, ∂²f/∂z_i∂z_j = v_i·v_j·∂²f/∂v_i∂v_j + δ_ij·v_i·∂f/∂v_i).
  bool exact(const Eigen::VectorXd& x, Eigen::VectorXd& g, Eigen::MatrixXd& h) const {
    if (!derivatives_) return false;
    const std::vector<double> v = coords_.values(x);
    if (!derivatives_(v, g, h) || !g.allFinite() || !h.allFinite()) return false;
    for (std::size_t i = 0; i < n_; ++i) {
      if (!params_[i].positive) continue;
      h.row(i) *= v[i];
      h.col(i) *= v[i];
      h(i, i) += v[i] * g[i];
      g[i] *= v[i];
    }
    return true;
  }

  // Central differences when the caller gives no exact derivatives (or not at x).
  void compute_gradient_hessian(const Eigen::VectorXd& x, double fx, Eigen::VectorXd& g, Eigen::MatrixXd& h) const {
    if (exact(x, g, h)) return;
    const auto& f = *this;
    const std::size_t n = n_;
    g.resize(n);
    h.resize(n, n);
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::VectorXd a = x, b = x;
      a[i] += coords_.step(i);
      b[i] -= coords_.step(i);
      const double fp = f(a), fm = f(b);
      g[i] = (fp - fm) / (2.0 * coords_.step(i));
      h(i, i) = (fp - 2.0 * fx + fm) / (coords_.step(i) * coords_.step(i));
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
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
    // An (almost) undamped step whose quadratic model promises next to nothing: the optimum, up to
    // the likelihood's rounding (raising the damping to find a step that still descends would cost
    // up to 30 evaluations for nothing).
    const double promised = -(g.dot(dz) + 0.5 * dz.dot(h * dz));
    if (tries == 0 && d.lambda <= 1e-2 && promised >= 0.0 && promised < 1e-9 * (1.0 + std::abs(d.fx))) {
      if (fn < d.fx) {
        d.z = zn;
        d.fx = fn;
      }
      converged = true;
      return true;
    }
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
    bool settled = false;  // an (almost) undamped step gained next to nothing: at the optimum
    for (int it = 0; it < max_iterations; ++it, ++r.iterations) {
      f.gradient_hessian(d.z, d.fx, g, h);
      if (!damped_newton_step(f, g, h, d, r.converged)) {
        r.converged = true;  // no descent step exists at this resolution: a (local) minimum
        break;
      }
      if (r.converged) {
        settled = true;
        break;
      }
    }
    // A restart is for a descent that stopped because no damped step descended or it ran out of
    // iterations; one that settled has nothing left to gain.
    if (settled || before_restart - d.fx < 1e-9 * (1.0 + std::abs(d.fx))) break;
  }
}

// A descent that settled where the Hessian has a clearly negative eigenvalue stopped at a saddle,
// not a minimum: a parameter used as |v| (σ_r, linear, so that it may reach 0) makes v = 0 a
// stationary point, and where the data want v > 0 the damped Newton steps cannot leave it (the
// gradient there is 0). Steps along that eigenvector, from the parameters' own scale down by tens
// (both signs), and the first that lowers the NLL is taken. Returns whether one did.
bool leave_saddle(Surface& f, const std::vector<FitParameter>& params, Descent& d) {
  const std::size_t n = params.size();
  if (n == 0) return false;
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  f.gradient_hessian(d.z, d.fx, g, h);
  const linalg::SymmetricEigen eig = linalg::symmetric_eigen(Eigen::MatrixXd(0.5 * (h + h.transpose())));
  Eigen::Index k = 0;
  const double lowest = eig.values.minCoeff(&k);
  if (!(lowest < -1e-9 * std::max(1.0, eig.values.maxCoeff()))) return false;
  const Eigen::VectorXd u = eig.vectors.col(k);
  double reach = 0.0;  // the eigenvector's length in the parameters' scales
  for (std::size_t i = 0; i < n; ++i)
    reach += std::abs(u[static_cast<Eigen::Index>(i)]) * (params[i].positive ? 1.0 : params[i].scale);
  for (double t = reach; t > 1e-6 * reach; t /= 10.0) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::VectorXd zn = d.z + sign * t * u;
      const double fn = f(zn);
      if (fn < d.fx) {
        d.z = zn;
        d.fx = fn;
        return true;
      }
    }
  }
  return false;
}

// Standard errors, 95% intervals and correlations from the Hessian at the optimum z.
void fill_intervals(Surface& f, const Eigen::VectorXd& z, double fx, const std::vector<FitParameter>& params,
                    FitResult& r) {
  const std::size_t n = params.size();
  Eigen::VectorXd g;
  Eigen::MatrixXd h;
  f.gradient_hessian(z, fx, g, h);
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
  for (int escape = 0; escape < 3 && leave_saddle(f, params, d); ++escape) descend(f, d, max_iterations, r);
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
