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
// Student-t's c(ν) − ½·log v − ½(ν + 1)·log1p(x²/(ν·v)).
inline Component component_density(double x, double v, const StudentConstant& k) {
  const Component r = Component::variable(x, kResidual, 3), var = Component::variable(v, kVariance, 3);
  if (!k.student) return -0.5 * (r * r / var + log(2.0 * kPi * var));
  const Component nu = Component::variable(k.nu, kDof, 3);
  Component constant = Component::zero(3);
  constant.v = k.c;
  constant.g[kDof] = k.c1;
  constant.h[5] = k.c2;  // (ν, ν) in the packed upper triangle of three
  return constant - 0.5 * log(var) - 0.5 * (nu + 1.0) * log1p(r * r / (nu * var));
}

}  // namespace locbench::diagnosis::chain
