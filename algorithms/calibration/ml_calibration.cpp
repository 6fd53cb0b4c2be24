#include "algorithms/calibration/ml_calibration.h"

#include <ceres/problem.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "algorithms/calibration/closed_form_calibration.h"
#include "algorithms/calibration/ml_calibration_solver.h"
#include "core/errors.h"
#include "core/linear_algebra.h"

namespace locbench::calibration {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using ml_solver::LmOutcome, ml_solver::Problem, ml_solver::Vector6, ml_solver::Whitening;

// Σᵢ⁻¹ᐟ² rᵢ for every active sample.
Eigen::VectorXd whiten(const Whitening& w, const Eigen::VectorXd& r) {
  Eigen::VectorXd e(r.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto k = 3 * static_cast<Eigen::Index>(i);
    e.segment<3>(k) = w[i] * r.segment<3>(k);
  }
  return e;
}

// ---- Noise model ----------------------------------------------------------------------------

struct NoiseState {
  NoiseModelKind kind = NoiseModelKind::kOdometryPropagated;
  Eigen::Vector3d values = Eigen::Vector3d::Zero();  // σ_x, σ_y, σ_θ or k, σ_t, σ_r
  double nll = kInf;                                 // −2 log-likelihood of the residuals it was estimated from
};

Eigen::Matrix3d sample_covariance(const NoiseState& n, const NoiseShape& shape) {
  if (n.kind == NoiseModelKind::kPerComponent) {
    return n.values.cwiseProduct(n.values).asDiagonal();
  }
  Eigen::Matrix3d S = n.values(0) * n.values(0) * shape.per_k2 + shape.quantization;
  S(0, 0) += n.values(1) * n.values(1);
  S(1, 1) += n.values(1) * n.values(1);
  S(2, 2) += n.values(2) * n.values(2);
  return S;
}

std::vector<NoiseShape> noise_shapes(const Problem& pb, const Vector6& v, double track) {
  std::vector<NoiseShape> shapes;
  const ModelParameters p = ModelParameters::from_vector(v);
  for (std::size_t i : pb.active) {
    shapes.push_back(odometry_noise_shape(pb.data, pb.data.samples[i], p, track));
  }
  return shapes;
}

// Whitening matrices; false if some Σᵢ is not positive definite.
bool whitening_of(const NoiseState& n, const std::vector<NoiseShape>& shapes, Whitening& w) {
  w.resize(shapes.size());
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const Eigen::LLT<Eigen::Matrix3d> llt(sample_covariance(n, shapes[i]));
    if (llt.info() != Eigen::Success) return false;
    w[i] = llt.matrixL().solve(Eigen::Matrix3d::Identity());
  }
  return true;
}

// −2 log-likelihood (up to a constant) of the residuals for variance components θ, with its
// gradient and expected Hessian (Fisher information) in φ = log θ:
// Σᵢ = Σ_c θ_c·A_ic + Qᵢ, A_i = (Pᵢ, diag(1, 1, 0), diag(0, 0, 1)),
// ∂/∂θ_c = Σᵢ tr(Σᵢ⁻¹A_ic) − uᵢᵀA_ic uᵢ (uᵢ = Σᵢ⁻¹rᵢ), E[∂²/∂θ_c∂θ_d] = Σᵢ tr(Σᵢ⁻¹A_icΣᵢ⁻¹A_id).
struct VarianceFit {
  double nll = kInf;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d fisher = Eigen::Matrix3d::Zero();
};
VarianceFit variance_fit(const Eigen::Vector3d& theta, const std::vector<NoiseShape>& shapes,
                         const Eigen::VectorXd& r) {
  VarianceFit f;
  f.nll = 0.0;
  Eigen::Matrix3d A[3];
  A[1] = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  A[2] = Eigen::Vector3d(0.0, 0.0, 1.0).asDiagonal();
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    A[0] = shapes[i].per_k2;
    const Eigen::Matrix3d S = theta(0) * A[0] + theta(1) * A[1] + theta(2) * A[2] + shapes[i].quantization;
    const double det = S.determinant();
    if (!(det > 0.0)) {
      f.nll = kInf;
      return f;
    }
    const Eigen::Matrix3d Si = S.inverse();
    const Eigen::Vector3d ri = r.segment<3>(3 * static_cast<Eigen::Index>(i));
    const Eigen::Vector3d u = Si * ri;
    f.nll += std::log(det) + u.dot(ri);
    Eigen::Matrix3d SA[3];
    for (int c = 0; c < 3; ++c) {
      SA[c] = Si * A[c];
      f.gradient(c) += SA[c].trace() - u.dot(A[c] * u);
    }
    for (int c = 0; c < 3; ++c) {
      for (int d = 0; d < 3; ++d) f.fisher(c, d) += (SA[c] * SA[d]).trace();
    }
  }
  // Chain rule to φ = log θ (the Fisher term only: scoring).
  f.gradient = f.gradient.cwiseProduct(theta);
  f.fisher = theta.asDiagonal() * f.fisher * theta.asDiagonal();
  return f;
}

// ML estimate of the noise state's unknown values from the residuals.
// kPerComponent: σ_c² = mean of the squared residual components (closed form).
// kOdometryPropagated: Fisher scoring on φ = log θ with a backtracking line search; each θ_c
// stays in [1e-18, 1] (units of k², m², rad²) and a component held at a bound by its gradient
// leaves the step (e.g. σ_t for exact ground truth goes to the lower bound).
NoiseState estimate_noise(const NoiseState& start, const std::vector<NoiseShape>& shapes, const Eigen::VectorXd& r) {
  NoiseState n = start;
  const auto m = static_cast<Eigen::Index>(shapes.size());
  if (n.kind == NoiseModelKind::kPerComponent) {
    for (int c = 0; c < 3; ++c) {
      double ss = 0.0;
      for (Eigen::Index i = 0; i < m; ++i) ss += r(3 * i + c) * r(3 * i + c);
      n.values(c) = std::max(std::sqrt(ss / static_cast<double>(m)), 1e-9);
    }
    n.nll = static_cast<double>(m) * (2.0 * n.values.array().log().sum() + 3.0);
    return n;
  }
  const double lo = std::log(1e-18), hi = 0.0;
  Eigen::Vector3d phi = n.values.cwiseProduct(n.values).cwiseMax(1e-12).array().log().matrix();
  phi = phi.cwiseMax(lo).cwiseMin(hi);
  VarianceFit fit = variance_fit(phi.array().exp().matrix(), shapes, r);
  for (int it = 0; it < 200 && std::isfinite(fit.nll); ++it) {
    // Active set: components not pinned at a bound by their gradient.
    std::vector<int> act;
    for (int c = 0; c < 3; ++c) {
      const bool at_lo = phi(c) <= lo + 1e-12 && fit.gradient(c) > 0.0;
      const bool at_hi = phi(c) >= hi - 1e-12 && fit.gradient(c) < 0.0;
      if (!at_lo && !at_hi) act.push_back(c);
    }
    if (act.empty()) break;
    const auto k = static_cast<Eigen::Index>(act.size());
    Eigen::MatrixXd I(k, k);
    Eigen::VectorXd g(k);
    for (Eigen::Index a = 0; a < k; ++a) {
      g(a) = fit.gradient(act[static_cast<std::size_t>(a)]);
      for (Eigen::Index b = 0; b < k; ++b) {
        I(a, b) = fit.fisher(act[static_cast<std::size_t>(a)], act[static_cast<std::size_t>(b)]);
      }
    }
    I.diagonal().array() += 1e-9 * I.diagonal().maxCoeff() + 1e-300;
    const Eigen::VectorXd step = linalg::ldlt_solve(I, -g).x;
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    for (Eigen::Index a = 0; a < k; ++a) dir(act[static_cast<std::size_t>(a)]) = step(a);
    const double longest = dir.cwiseAbs().maxCoeff();
    if (longest > 5.0) dir *= 5.0 / longest;  // at most a factor e⁵ per iteration
    bool improved = false;
    for (double t = 1.0; t > 1e-4; t *= 0.5) {
      const Eigen::Vector3d trial = (phi + t * dir).cwiseMax(lo).cwiseMin(hi);
      const VarianceFit next = variance_fit(trial.array().exp().matrix(), shapes, r);
      if (next.nll < fit.nll) {
        const double gain = fit.nll - next.nll;
        phi = trial;
        fit = next;
        improved = gain > 1e-9;
        break;
      }
    }
    if (!improved) break;
  }
  n.values = (0.5 * phi).array().exp().matrix();
  n.nll = fit.nll;
  return n;
}

// The alternation has converged when re-estimating the noise no longer changes the likelihood
// of the residuals noticeably (values heading for a bound may still creep).
bool noise_converged(const NoiseState& a, const NoiseState& b) { return std::abs(a.nll - b.nll) < 1e-3; }

// ---- One solve on a set of samples ----------------------------------------------------------

struct Solution {
  Vector6 values;
  ModelParameters closed_form;
  NoiseState noise;
  Whitening whitening;
  int iterations = 0;
  bool converged = false;
};

// "3 samples give 9 measurements for 6 free parameters after outlier rejection: expected …".
std::string too_few_samples(std::size_t samples, std::size_t free, const char* when) {
  return std::to_string(samples) + " samples give " + std::to_string(3 * samples) + " measurements for " +
         std::to_string(free) + " free parameters" + when +
         ": expected more measurements than free parameters (at least " + std::to_string(free / 3 + 1) + " samples)";
}

Solution solve(const Problem& pb, const ParameterMask& free_mask, const ModelParameters& start,
               const MlCalibrationOptions& opt) {
  Solution sol;
  CalibrationData active_data = subset(pb.data, 0, 0);
  for (std::size_t i : pb.active) active_data.samples.push_back(pb.data.samples[i]);
  sol.closed_form = closed_form_calibration(active_data, start, free_mask).parameters;

  Problem p = pb;
  p.base = sol.closed_form.vector();
  Eigen::VectorXd x = p.free_values(p.base);
  NoiseState noise;
  noise.kind = opt.noise.kind;
  noise.values = opt.noise.kind == NoiseModelKind::kPerComponent
                     ? Eigen::Vector3d(opt.noise.sigma_x, opt.noise.sigma_y, opt.noise.sigma_theta)
                     : Eigen::Vector3d(opt.noise.k, opt.noise.sigma_translation, opt.noise.sigma_rotation);
  if (opt.noise.estimate) {
    // Start the noise from the closed form's residuals.
    noise = estimate_noise(noise, noise_shapes(p, p.full(x), opt.noise.virtual_track), p.residuals(p.full(x)));
  }
  const int rounds = opt.noise.estimate ? std::max(1, opt.noise_iterations) : 1;
  sol.whitening.resize(p.active.size());
  const auto problem = x.size() > 0 ? ml_solver::whitened_problem(p, sol.whitening, x) : nullptr;
  for (int round = 0; round < rounds; ++round) {
    const auto shapes = noise_shapes(p, p.full(x), opt.noise.virtual_track);
    if (!whitening_of(noise, shapes, sol.whitening)) {
      throw InputError(pb.data.source, 0,
                       "a sample's noise covariance is not positive definite (degenerate samples, e.g. no "
                       "motion at all): expected samples whose motions give every noise term a positive variance");
    }
    if (problem) ml_solver::restrict_to_determined(*problem, x);
    const LmOutcome lm = problem ? ml_solver::levenberg_marquardt(*problem, x, opt.max_iterations) : LmOutcome{0, true};
    sol.iterations += lm.iterations;
    sol.converged = lm.converged;
    if (!opt.noise.estimate) break;
    const NoiseState next =
        estimate_noise(noise, noise_shapes(p, p.full(x), opt.noise.virtual_track), p.residuals(p.full(x)));
    const bool done = noise_converged(noise, next);
    noise = next;
    if (done) break;
  }
  // Whitening with the final noise values for the covariance and χ².
  whitening_of(noise, noise_shapes(p, p.full(x), opt.noise.virtual_track), sol.whitening);
  sol.values = p.full(x);
  sol.noise = noise;
  return sol;
}

// Censi et al.'s rule: keep the samples whose ‖(Δx, Δy)‖ and |Δθ| are both at most the
// (1 − fraction) quantile of their kind.
std::vector<std::size_t> drop_outliers(const Problem& pb, const Vector6& v, double fraction) {
  const Eigen::VectorXd r = pb.residuals(v);
  const std::size_t n = pb.active.size();
  std::vector<double> xy(n), th(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = 3 * static_cast<Eigen::Index>(i);
    xy[i] = std::hypot(r(k), r(k + 1));
    th[i] = std::abs(r(k + 2));
  }
  auto threshold = [&](std::vector<double> v2) {
    std::sort(v2.begin(), v2.end());
    auto idx = static_cast<long>(std::lround((1.0 - fraction) * static_cast<double>(n)));
    idx = std::clamp(idx, 0L, static_cast<long>(n) - 1);
    return v2[static_cast<std::size_t>(idx)];
  };
  const double txy = threshold(xy), tth = threshold(th);
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < n; ++i) {
    if (xy[i] <= txy && th[i] <= tth) keep.push_back(pb.active[i]);
  }
  return keep;
}

}  // namespace

const CalibratedParameter& MlCalibrationResult::parameter(const std::string& name) const {
  for (const CalibratedParameter& p : parameters) {
    if (p.name == name) return p;
  }
  throw std::out_of_range("no estimated parameter named " + name);
}

MlCalibrationResult calibrate_ml(const CalibrationData& data, const MlCalibrationOptions& opt) {
  if (data.samples.empty()) throw InputError(data.source, 0, "no calibration samples: expected at least one");
  for (const CalibrationSample& s : data.samples) {
    if (!is_finite(s)) throw InputError(data.source, 0, "a calibration sample is not finite: expected finite numbers");
  }
  if (opt.outliers.iterations < 0 || !(opt.outliers.fraction > 0.0) || !(opt.outliers.fraction <= 0.5)) {
    throw std::invalid_argument("calibrate_ml: outliers need iterations >= 0, 0 < fraction <= 0.5");
  }
  if (opt.max_iterations < 1 || !(opt.noise.virtual_track > 0.0)) {
    throw std::invalid_argument("calibrate_ml: max_iterations >= 1 and virtual_track > 0 needed");
  }
  if (!opt.noise.estimate &&
      (opt.noise.kind == NoiseModelKind::kPerComponent
           ? !(opt.noise.sigma_x > 0.0 && opt.noise.sigma_y > 0.0 && opt.noise.sigma_theta > 0.0)
           : !(opt.noise.k >= 0.0 && opt.noise.sigma_translation > 0.0 && opt.noise.sigma_rotation > 0.0))) {
    throw std::invalid_argument("calibrate_ml: fixed noise values must be positive");
  }

  // Names and free parameters.
  const auto odo_names = odometry_parameter_names(data.kind);
  const auto sensor_names = sensor_parameter_names();
  std::array<std::string, 6> names;
  for (int j = 0; j < 3; ++j) {
    names[static_cast<std::size_t>(j)] = odo_names[static_cast<std::size_t>(j)];
    names[static_cast<std::size_t>(j) + 3] = sensor_names[static_cast<std::size_t>(j)];
  }
  const bool wheels = data.kind == OdometryInputKind::kWheelTicks || data.kind == OdometryInputKind::kWheelAngles;
  ParameterMask free{true, true, wheels, false, false, false};
  if (data.kind == OdometryInputKind::kBodyIncrements) free[2] = opt.estimate_rotation_per_distance;
  if (data.kind == OdometryInputKind::kVelocityIntegrals) free[2] = opt.estimate_rotation_rate_bias;
  if (data.sensor_reference && opt.estimate_sensor_pose) free[3] = free[4] = free[5] = true;
  for (const std::string& f : opt.fixed) {
    const auto it = std::find(names.begin(), names.end(), f);
    if (it == names.end()) throw std::invalid_argument("calibrate_ml: unknown parameter " + f);
    free[static_cast<std::size_t>(it - names.begin())] = false;
  }

  Problem pb{data, {}, {}, nominal_parameters(data).vector()};
  for (int j = 0; j < 6; ++j) {
    if (free[static_cast<std::size_t>(j)]) pb.free.push_back(j);
  }
  for (std::size_t i = 0; i < data.samples.size(); ++i) pb.active.push_back(i);
  if (3 * pb.active.size() <= pb.free.size()) {
    throw InputError(data.source, 0, too_few_samples(pb.active.size(), pb.free.size(), ""));
  }

  const ModelParameters start = nominal_parameters(data);
  MlCalibrationResult res;
  Solution sol = solve(pb, free, start, opt);
  res.iterations = sol.iterations;
  for (int it = 0; it < opt.outliers.iterations; ++it) {
    pb.active = drop_outliers(pb, sol.values, opt.outliers.fraction);
    if (3 * pb.active.size() <= pb.free.size()) {
      throw InputError(data.source, 0, too_few_samples(pb.active.size(), pb.free.size(), " after outlier rejection"));
    }
    sol = solve(pb, free, start, opt);
    res.iterations += sol.iterations;
  }

  // Fisher information at the solution and what it determines.
  Problem fin = pb;
  fin.base = sol.values;
  Eigen::VectorXd x = fin.free_values(sol.values);
  const auto rows = 3 * static_cast<Eigen::Index>(pb.active.size());
  const Eigen::MatrixXd J =
      x.size() > 0 ? ml_solver::whitened_jacobian(*ml_solver::whitened_problem(fin, sol.whitening, x), rows, x.size())
                   : Eigen::MatrixXd(rows, 0);
  const Eigen::MatrixXd F = J.transpose() * J;
  // A square root of F (F = RᵀR) carries the same information as the whitened Jacobian itself,
  // in p rows instead of 3n (identifiability.h would otherwise need a 3n × 3n identity).
  const linalg::SymmetricEigen eig = linalg::symmetric_eigen(F);
  const Eigen::MatrixXd R = eig.values.cwiseMax(0.0).cwiseSqrt().asDiagonal() * eig.vectors.transpose();
  std::vector<std::string> free_names;
  for (int j : pb.free) free_names.push_back(names[static_cast<std::size_t>(j)]);
  res.identifiability = analyze_identifiability(R, Eigen::MatrixXd::Identity(R.rows(), R.rows()), free_names, x,
                                                opt.identifiability_tolerance);
  res.covariance = res.identifiability.covariance;

  res.kind = data.kind;
  res.estimate = ModelParameters::from_vector(sol.values);
  res.closed_form = sol.closed_form;
  const Vector6 nominal = nominal_parameters(data).vector();
  const Vector6 closed = sol.closed_form.vector();
  for (std::size_t j = 0; j < pb.free.size(); ++j) {
    const int k = pb.free[j];
    const ParameterFinding& f = res.identifiability.parameters[j];
    res.parameters.push_back({names[static_cast<std::size_t>(k)], sol.values(k), nominal(k), f.standard_error,
                              closed(k), f.identifiable, f.reason});
  }
  res.noise_kind = sol.noise.kind;
  res.noise = sol.noise.values;

  const Eigen::VectorXd r = fin.residuals(sol.values);
  const Eigen::VectorXd e = whiten(sol.whitening, r);
  double st = 0.0, sr = 0.0;
  const auto m = static_cast<Eigen::Index>(pb.active.size());
  for (Eigen::Index i = 0; i < m; ++i) {
    st += r(3 * i) * r(3 * i) + r(3 * i + 1) * r(3 * i + 1);
    sr += r(3 * i + 2) * r(3 * i + 2);
  }
  res.samples_used = pb.active.size();
  res.samples_rejected = data.samples.size() - pb.active.size();
  res.residual_rms_translation = std::sqrt(st / static_cast<double>(m));
  res.residual_rms_rotation = std::sqrt(sr / static_cast<double>(m));
  res.chi2 = e.squaredNorm();
  res.dof = static_cast<double>(3 * pb.active.size() - pb.free.size());
  res.chi2_per_dof = res.chi2 / res.dof;
  res.used.assign(data.samples.size(), false);
  for (std::size_t i : pb.active) res.used[i] = true;
  res.converged = sol.converged;
  return res;
}

}  // namespace locbench::calibration
