#pragma once
// One residual component's log-density — normal, or Student-t with ν degrees of freedom — with
// its first and second derivatives in (residual, variance, ν): the building block of the
// likelihood derivatives by the chain rule (odometry_derivatives.cpp, landmark_derivatives.cpp).
// A channel's likelihood depends on its fitted fields through a few such inner quantities per
// window or reading; differentiating each component over three numbers and mapping the result to
// the fields through a sparse Jacobian costs a fraction of carrying the Hessian of every field
// through every operation.
#include <cmath>

#include "algorithms/diagnosis/hyper_dual.h"
#include "core/units.h"

namespace locbench::diagnosis::chain {

using Component = HyperDual<3>;  // over (residual, variance, ν)
enum ComponentVariable { kResidual = 0, kVariance = 1, kDof = 2 };

// The Student-t constant lgamma((ν+1)/2) − lgamma(ν/2) − ½·log(νπ) and its derivatives in ν,
// computed once per likelihood (ν ≤ 0: the normal density).
struct StudentConstant {
  bool student = false;
  double nu = 0.0, c = 0.0, c1 = 0.0, c2 = 0.0;
  explicit StudentConstant(double dof) : student(dof > 0.0), nu(dof) {
    if (!student) return;
    c = std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) - 0.5 * std::log(nu * kPi);
    c1 = 0.5 * digamma(0.5 * (nu + 1.0)) - 0.5 * digamma(0.5 * nu) - 0.5 / nu;
    c2 = 0.25 * trigamma(0.5 * (nu + 1.0)) - 0.25 * trigamma(0.5 * nu) + 0.5 / (nu * nu);
  }
};

// The log-density of residual x under variance (squared scale) v: −½(x²/v + log 2πv), or the
// Student-t's c(ν) − ½·log v − w·log1p(q) with w = (ν + 1)/2 and q = x²/(ν·v); its derivatives in
// closed form (the chain rule through q: L = log1p(q), L' = 1/(1 + q), L'' = −L'²).
inline Component component_density(double x, double v, const StudentConstant& k) {
  Component d = Component::zero(3);
  double* g = d.g;
  double* h = d.h;  // packed upper triangle: (x,x) (x,v) (x,ν) (v,v) (v,ν) (ν,ν)
  if (!k.student) {
    d.v = -0.5 * (x * x / v + std::log(2.0 * kPi * v));
    g[kResidual] = -x / v;
    g[kVariance] = 0.5 * x * x / (v * v) - 0.5 / v;
    h[0] = -1.0 / v;
    h[1] = x / (v * v);
    h[3] = -x * x / (v * v * v) + 0.5 / (v * v);
    return d;
  }
  const double nu = k.nu, w = 0.5 * (nu + 1.0);
  const double q = x * x / (nu * v);
  const double l1 = 1.0 / (1.0 + q), l2 = -l1 * l1;
  const double qx = 2.0 * x / (nu * v), qxx = 2.0 / (nu * v);
  const double qv = -q / v, qvv = 2.0 * q / (v * v), qxv = -qx / v;
  const double qn = -q / nu, qnn = 2.0 * q / (nu * nu), qxn = -qx / nu, qvn = q / (v * nu);
  const double lq = std::log1p(q);
  d.v = k.c - 0.5 * std::log(v) - w * lq;
  g[kResidual] = -w * l1 * qx;
  g[kVariance] = -0.5 / v - w * l1 * qv;
  g[kDof] = k.c1 - 0.5 * lq - w * l1 * qn;
  h[0] = -w * (l2 * qx * qx + l1 * qxx);
  h[1] = -w * (l2 * qx * qv + l1 * qxv);
  h[2] = -0.5 * l1 * qx - w * (l2 * qx * qn + l1 * qxn);
  h[3] = 0.5 / (v * v) - w * (l2 * qv * qv + l1 * qvv);
  h[4] = -0.5 * l1 * qv - w * (l2 * qv * qn + l1 * qvn);
  h[5] = k.c2 - l1 * qn - w * (l2 * qn * qn + l1 * qnn);
  return d;
}

}  // namespace locbench::diagnosis::chain
