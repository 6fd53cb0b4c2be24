#include "algorithms/diagnosis/landmark_derivatives.h"

#include <algorithm>
#include <cmath>
#include <iterator>

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
  // landmark_nll's +inf, and its floor on σ_r² (below it the plain likelihood is not this formula).
  const bool range_noise = m.sigma_range > 0.0 || (m.sigma_range == 0.0 && m.range_noise_slope > 0.0);
  if (!range_noise || !(m.sigma_bearing > 0.0) || !(m.range_scale > 0.0) || m.dof < 0.0 ||
      m.sigma_range * m.sigma_range < 1e-12) {
    return std::nullopt;
  }
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
    if (!r.valid) {
      nll = nll - (density(Number(0.0), v_r0) + density(Number(0.0), v_b0));
      continue;
    }
    const LandmarkGeometry& g = geometry[i];
    Number rho(r.rho), phi(r.phi);
    const MapLandmark& lm = d.map[static_cast<std::size_t>(d.landmark[i])];
    if (lm.id == m.position_error_id) {  // the moved landmark: its prediction depends on δ
      const Number dx = lm.x + dx_error - g.x, dy = lm.y + dy_error - g.y;
      rho = with_value(sqrt(dx * dx + dy * dy), r.rho);
      phi = with_value(atan2(dy, dx), r.phi);
    }
    const Number held =
        std::abs(r.phi) <= m.field_of_view ? phi : Number(std::clamp(r.phi, -m.field_of_view, m.field_of_view));
    const Number range = d.readings[i].range - ((scale0 + (linear + quadratic * held) * held) * rho + bias);
    const Number bearing = with_value(-phi - bearing_bias, r.bearing);
    const Number s = slope * rho, sb = turn_slope * g.turn_rate;
    nll = nll - (density(range, v_r0 + s * s) + density(bearing, v_b0 + sb * sb));
  }
  gradient.resize(n);
  hessian.resize(n, n);
  for (int a = 0; a < n; ++a) {
    gradient[a] = nll.g[a];
    for (int b = 0; b < n; ++b) hessian(a, b) = nll.hessian(a, b);
  }
  return nll.v;
}

}  // namespace landmark_ad

std::optional<double> landmark_nll_derivatives(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry,
                                               const LandmarkModel& m, const std::vector<std::size_t>& index,
                                               const std::vector<double LandmarkModel::*>& fields,
                                               Eigen::VectorXd& gradient, Eigen::MatrixXd& hessian) {
  return landmark_ad::derivatives(d, geometry, m, index, fields, gradient, hessian);
}

}  // namespace locbench::diagnosis
