#include "algorithms/diagnosis/landmark_derivatives.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <utility>

#include "algorithms/diagnosis/component_density.h"
#include "algorithms/diagnosis/hyper_dual.h"
#include "core/angle.h"

namespace locbench::diagnosis {
// The differentiated formulas' own names (a unity build batches this file with the plain ones).
namespace landmark_ad {
namespace {

using Number = HyperDual<kMaxLandmarkDifferentiatedFields>;
using Field = double LandmarkModel::*;

// The differentiable fields, each a parameter of the fit or a constant.
constexpr Field kDifferentiable[] = {&LandmarkModel::range_scale,
                                     &LandmarkModel::range_bias,
                                     &LandmarkModel::range_off_axis_linear,
                                     &LandmarkModel::range_off_axis,
                                     &LandmarkModel::bearing_bias,
                                     &LandmarkModel::sigma_range,
                                     &LandmarkModel::sigma_bearing,
                                     &LandmarkModel::range_noise_slope,
                                     &LandmarkModel::bearing_noise_turn_slope,
                                     &LandmarkModel::dof,
                                     &LandmarkModel::position_error_dx,
                                     &LandmarkModel::position_error_dy};
constexpr std::size_t kFields = std::size(kDifferentiable);

struct Parameters {
  Number value[kFields];
  const Number& operator[](Field f) const {
    return value[std::find(std::begin(kDifferentiable), std::end(kDifferentiable), f) - std::begin(kDifferentiable)];
  }
};

// Log-density of a residual r with squared scale v: normal (dof = 0) or Student-t, as
// LandmarkDensity in landmark_model.cpp.
struct Density {
  explicit Density(const Number& nu) : dof(nu), student(nu.v > 0.0) {
    constant = student ? lgamma(0.5 * (nu + 1.0)) - lgamma(0.5 * nu) - 0.5 * log(nu * kPi)
                       : Number(-0.5 * std::log(2.0 * kPi));
  }
  Number operator()(const Number& r, const Number& v) const {
    if (!student) return constant - 0.5 * (r * r / v + log(v));
    return constant - 0.5 * log(v) - 0.5 * (dof + 1.0) * log1p(r * r / (dof * v));
  }
  Number dof;
  bool student;
  Number constant;
};

// x's derivatives with the value v (a wrapped residual: the wrap moves the value, not the slope).
Number with_value(Number x, double v) {
  x.v = v;
  return x;
}

// ∂u/∂field of an inner quantity u (a residual, a variance, ν) for one fitted field (−1: not
// fitted, skipped).
struct Slope {
  int inner;  // chain::kResidual, kVariance or kDof
  int field;
  double d;
};

// Adds −(a component's log-density) to the NLL's gradient g and Hessian h through the slopes of
// its inner quantities, and the variance's own second derivatives `curvature` (field, ∂²v/∂field²).
void subtract_component(const chain::Component& D, std::initializer_list<Slope> slopes,
                        std::initializer_list<std::pair<int, double>> curvature, Eigen::VectorXd& g,
                        Eigen::MatrixXd& h) {
  for (const Slope& a : slopes) {
    if (a.field < 0) continue;
    g[a.field] -= D.g[a.inner] * a.d;
    for (const Slope& b : slopes) {
      if (b.field >= 0) h(a.field, b.field) -= D.hessian(a.inner, b.inner) * a.d * b.d;
    }
  }
  for (const auto& [field, second] : curvature) {
    if (field >= 0) h(field, field) -= D.g[chain::kVariance] * second;
  }
}

// The readings' NLL and its derivatives by the chain rule, all readings but those of the moved
// landmark when `skip_moved` (its prediction depends on the position error; the hyper-dual pass
// takes them): a reading's range residual is linear in the range scale, the off-axis terms and
// the bias, its bearing residual in the bearing bias, and their variances σ² + (slope·ρ)²,
// σ_φ² + (slope·ω)² quadratic in the noise fields; each residual's density is differentiated
// over (residual, variance, ν) alone (component_density.h).
double chain_derivatives(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry, const LandmarkModel& m,
                         const std::vector<std::size_t>& index, const std::vector<Field>& fields, bool skip_moved,
                         Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
  using chain::kDof;
  using chain::kResidual;
  using chain::kVariance;
  const int n = static_cast<int>(fields.size());
  auto at = [&](Field f) {
    const auto it = std::find(fields.begin(), fields.end(), f);
    return it == fields.end() ? -1 : static_cast<int>(it - fields.begin());
  };
  const int i_scale = at(&LandmarkModel::range_scale), i_linear = at(&LandmarkModel::range_off_axis_linear),
            i_quadratic = at(&LandmarkModel::range_off_axis), i_bias = at(&LandmarkModel::range_bias),
            i_bearing_bias = at(&LandmarkModel::bearing_bias), i_sigma_r = at(&LandmarkModel::sigma_range),
            i_sigma_b = at(&LandmarkModel::sigma_bearing), i_slope = at(&LandmarkModel::range_noise_slope),
            i_turn_slope = at(&LandmarkModel::bearing_noise_turn_slope), i_dof = at(&LandmarkModel::dof);
  const chain::StudentConstant student(m.dof);
  const double v_r0 = m.sigma_range * m.sigma_range, v_b0 = m.sigma_bearing * m.sigma_bearing;
  gradient = Eigen::VectorXd::Zero(n);
  hessian = Eigen::MatrixXd::Zero(n, n);
  double nll = 0.0;
  const std::size_t count = index.empty() ? d.readings.size() : index.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = index.empty() ? k : index[k];
    const LandmarkResidual r = landmark_residual(d, i, geometry[i], m);
    if (skip_moved && r.valid && d.map[static_cast<std::size_t>(d.landmark[i])].id == m.position_error_id) continue;
    const LandmarkGeometry& g = geometry[i];
    double range = 0.0, bearing = 0.0, v_r = v_r0, v_b = v_b0;
    double rho = 0.0, held = 0.0;
    if (r.valid) {
      rho = r.rho;
      held = std::abs(r.phi) <= m.field_of_view ? r.phi : std::clamp(r.phi, -m.field_of_view, m.field_of_view);
      range = d.readings[i].range -
              ((m.range_scale + (m.range_off_axis_linear + m.range_off_axis * held) * held) * rho + m.range_bias);
      bearing = r.bearing;
      const double s = m.range_noise_slope * rho, sb = m.bearing_noise_turn_slope * g.turn_rate;
      v_r = v_r0 + s * s;
      v_b = v_b0 + sb * sb;
    }
    const chain::Component dr = chain::component_density(range, v_r, student);
    const chain::Component db = chain::component_density(bearing, v_b, student);
    nll -= dr.v + db.v;
    if (!r.valid) {  // not covered: the constant of a perfect fit
      subtract_component(dr, {{kVariance, i_sigma_r, 2.0 * m.sigma_range}, {kDof, i_dof, 1.0}}, {{i_sigma_r, 2.0}},
                         gradient, hessian);
      subtract_component(db, {{kVariance, i_sigma_b, 2.0 * m.sigma_bearing}, {kDof, i_dof, 1.0}}, {{i_sigma_b, 2.0}},
                         gradient, hessian);
      continue;
    }
    subtract_component(dr,
                       {{kResidual, i_scale, -rho},
                        {kResidual, i_linear, -rho * held},
                        {kResidual, i_quadratic, -rho * held * held},
                        {kResidual, i_bias, -1.0},
                        {kVariance, i_sigma_r, 2.0 * m.sigma_range},
                        {kVariance, i_slope, 2.0 * m.range_noise_slope * rho * rho},
                        {kDof, i_dof, 1.0}},
                       {{i_sigma_r, 2.0}, {i_slope, 2.0 * rho * rho}}, gradient, hessian);
    const double omega2 = g.turn_rate * g.turn_rate;
    subtract_component(db,
                       {{kResidual, i_bearing_bias, -1.0},
                        {kVariance, i_sigma_b, 2.0 * m.sigma_bearing},
                        {kVariance, i_turn_slope, 2.0 * m.bearing_noise_turn_slope * omega2},
                        {kDof, i_dof, 1.0}},
                       {{i_sigma_b, 2.0}, {i_turn_slope, 2.0 * omega2}}, gradient, hessian);
  }
  return nll;
}

}  // namespace

std::optional<double> derivatives(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                  const LandmarkModel& m, const std::vector<std::size_t>& index,
                                  const std::vector<Field>& fields, Eigen::VectorXd& gradient,
                                  Eigen::MatrixXd& hessian) {
  const int n = static_cast<int>(fields.size());
  if (n > kMaxLandmarkDifferentiatedFields) return std::nullopt;
  for (Field f : fields) {
    if (std::find(std::begin(kDifferentiable), std::end(kDifferentiable), f) == std::end(kDifferentiable)) {
      return std::nullopt;
    }
  }
  // landmark_nll's +inf, and its floor on σ_r²: below it the plain likelihood is not this formula
  // where it uses σ_r² alone (a reading the truth does not cover, or no range-dependent noise). With
  // a slope every covered reading's variance is σ_r² + (slope·ρ)² in both, so σ_r at its boundary 0
  // (the slope explains the range noise) keeps its exact derivatives.
  const bool range_noise = m.sigma_range > 0.0 || (m.sigma_range == 0.0 && m.range_noise_slope > 0.0);
  if (!range_noise || !(m.sigma_bearing > 0.0) || !(m.range_scale > 0.0) || m.dof < 0.0) return std::nullopt;
  if (m.sigma_range * m.sigma_range < 1e-12) {
    const std::size_t count = index.empty() ? d.readings.size() : index.size();
    bool floored = !(m.range_noise_slope > 0.0);
    for (std::size_t k = 0; k < count && !floored; ++k) floored = !geometry[index.empty() ? k : index[k]].valid;
    if (floored) return std::nullopt;
  }
  // Every reading but the moved landmark's by the chain rule; those (their prediction depends on the
  // position error when it is fitted) on hyper-dual numbers below.
  const bool moved_fitted = std::any_of(fields.begin(), fields.end(), [](Field f) {
    return f == &LandmarkModel::position_error_dx || f == &LandmarkModel::position_error_dy;
  });
  const double chained = chain_derivatives(d, geometry, m, index, fields, moved_fitted, gradient, hessian);
  if (!moved_fitted) return chained;
  Parameters p;
  for (std::size_t k = 0; k < kFields; ++k) {
    const auto it = std::find(fields.begin(), fields.end(), kDifferentiable[k]);
    const double x = m.*kDifferentiable[k];
    p.value[k] = it == fields.end() ? Number(x) : Number::variable(x, static_cast<int>(it - fields.begin()), n);
  }
  const Density density(p[&LandmarkModel::dof]);
  const Number &sigma_r = p[&LandmarkModel::sigma_range], &sigma_b = p[&LandmarkModel::sigma_bearing];
  const Number &scale0 = p[&LandmarkModel::range_scale], &linear = p[&LandmarkModel::range_off_axis_linear],
               &quadratic = p[&LandmarkModel::range_off_axis], &bias = p[&LandmarkModel::range_bias],
               &bearing_bias = p[&LandmarkModel::bearing_bias], &slope = p[&LandmarkModel::range_noise_slope],
               &turn_slope = p[&LandmarkModel::bearing_noise_turn_slope],
               &dx_error = p[&LandmarkModel::position_error_dx], &dy_error = p[&LandmarkModel::position_error_dy];
  const Number v_r0 = sigma_r * sigma_r, v_b0 = sigma_b * sigma_b;
  Number nll = Number::zero(n);
  const std::size_t count = index.empty() ? d.readings.size() : index.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = index.empty() ? k : index[k];
    const LandmarkResidual r = landmark_residual(d, i, geometry[i], m);
    const MapLandmark& lm = d.map[static_cast<std::size_t>(d.landmark[i])];
    if (!r.valid || lm.id != m.position_error_id) continue;  // by the chain rule above
    const LandmarkGeometry& g = geometry[i];
    // The moved landmark: its prediction depends on δ.
    const Number dx = lm.x + dx_error - g.x, dy = lm.y + dy_error - g.y;
    const Number rho = with_value(sqrt(dx * dx + dy * dy), r.rho);
    const Number phi = with_value(atan2(dy, dx), r.phi);
    const Number held =
        std::abs(r.phi) <= m.field_of_view ? phi : Number(std::clamp(r.phi, -m.field_of_view, m.field_of_view));
    const Number range = d.readings[i].range - ((scale0 + (linear + quadratic * held) * held) * rho + bias);
    const Number bearing = with_value(-phi - bearing_bias, r.bearing);
    const Number s = slope * rho, sb = turn_slope * g.turn_rate;
    nll = nll - (density(range, v_r0 + s * s) + density(bearing, v_b0 + sb * sb));
  }
  for (int a = 0; a < n; ++a) {
    gradient[a] += nll.g[a];
    for (int b = 0; b < n; ++b) hessian(a, b) += nll.hessian(a, b);
  }
  return chained + nll.v;
}

}  // namespace landmark_ad

std::optional<double> landmark_nll_derivatives(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                               const LandmarkModel& m, const std::vector<std::size_t>& index,
                                               const std::vector<double LandmarkModel::*>& fields,
                                               Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
  return landmark_ad::derivatives(d, geometry, m, index, fields, gradient, hessian);
}

}  // namespace locbench::diagnosis
