#pragma once
// Second-order forward-mode automatic differentiation: a number that carries its value, its
// gradient and its Hessian (upper triangle, packed by rows) with respect to n ≤ C parameters.
// The likelihood derivatives of the fits (odometry_derivatives.cpp) are computed with it: one
// evaluation gives the exact gradient and Hessian, instead of the 2n² likelihood evaluations of
// central differences. A constant has n = 0; the operands of a binary operation have the same n
// or one of them is a constant. The value is computed with the same double operations as the
// plain expression (a·b, a/b, std::sin(a), …), so a HyperDual's value equals the double result.
#include <cassert>
#include <cmath>

// The operations are forced inline: called per arithmetic operation of the likelihood, a call
// costs as much as the loops.
#define LOCBENCH_HD_INLINE inline __attribute__((always_inline))

// The gradient and Hessian arrays are read only up to n, and n = 0 for a constant, whose arrays are
// left unset (filling 90 doubles per constant would cost as much as the arithmetic); GCC 12 cannot
// see that through the n == 0 branches and warns "may be used uninitialized" under -O1 with the
// sanitizers, which -Werror makes fatal.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace locbench::diagnosis {

template <int C>
struct HyperDual {
  static constexpr int kCapacity = C;
  static constexpr int kPacked = C * (C + 1) / 2;
  int n = 0;
  double v = 0.0;
  double g[C];
  double h[kPacked];

  HyperDual() = default;
  HyperDual(double value) : v(value) {}  // NOLINT: a constant converts implicitly
  // The i-th of n parameters with value x.
  static HyperDual variable(double x, int i, int n) {
    HyperDual r = zero(n);
    r.v = x;
    r.g[i] = 1.0;
    return r;
  }
  static HyperDual zero(int n) {
    assert(n <= C);
    HyperDual r;
    r.n = n;
    for (int i = 0; i < n; ++i) r.g[i] = 0.0;
    for (int k = 0; k < n * (n + 1) / 2; ++k) r.h[k] = 0.0;
    return r;
  }
  int packed() const { return n * (n + 1) / 2; }
  // A copy of the n entries in use (a plain copy moves all C + C(C+1)/2 of them).
  LOCBENCH_HD_INLINE HyperDual used_copy() const {
    HyperDual r;
    r.n = n;
    r.v = v;
    for (int i = 0; i < n; ++i) r.g[i] = g[i];
    for (int k = 0; k < packed(); ++k) r.h[k] = h[k];
    return r;
  }
  double hessian(int i, int j) const {
    if (i > j) return hessian(j, i);
    return h[i * n - i * (i - 1) / 2 + (j - i)];
  }

  // f(this) given f(v), f'(v), f''(v).
  LOCBENCH_HD_INLINE HyperDual apply(double f0, double f1, double f2) const {
    HyperDual r;
    r.n = n;
    r.v = f0;
    for (int i = 0, k = 0; i < n; ++i) {
      r.g[i] = f1 * g[i];
      for (int j = i; j < n; ++j, ++k) r.h[k] = f1 * h[k] + f2 * g[i] * g[j];
    }
    return r;
  }
};

template <int C>
inline double value_of(const HyperDual<C>& a) {
  return a.v;
}
inline double value_of(double a) { return a; }

template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator-(const HyperDual<C>& a) {
  return a.apply(-a.v, -1.0, 0.0);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator+(const HyperDual<C>& a, const HyperDual<C>& b) {
  if (a.n == 0) {
    HyperDual<C> r = b.used_copy();
    r.v = a.v + b.v;
    return r;
  }
  HyperDual<C> r = a.used_copy();
  r.v = a.v + b.v;
  if (b.n == 0) return r;
  assert(a.n == b.n);
  for (int i = 0; i < a.n; ++i) r.g[i] += b.g[i];
  for (int k = 0; k < a.packed(); ++k) r.h[k] += b.h[k];
  return r;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator-(const HyperDual<C>& a, const HyperDual<C>& b) {
  if (a.n == 0) {
    HyperDual<C> r = -b;
    r.v = a.v - b.v;
    return r;
  }
  HyperDual<C> r = a.used_copy();
  r.v = a.v - b.v;
  if (b.n == 0) return r;
  assert(a.n == b.n);
  for (int i = 0; i < a.n; ++i) r.g[i] -= b.g[i];
  for (int k = 0; k < a.packed(); ++k) r.h[k] -= b.h[k];
  return r;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator*(const HyperDual<C>& a, const HyperDual<C>& b) {
  if (a.n == 0 || b.n == 0) {
    const HyperDual<C>& x = a.n == 0 ? b : a;
    const double s = a.n == 0 ? a.v : b.v;
    HyperDual<C> r = x.apply(0.0, s, 0.0);
    r.v = a.v * b.v;
    return r;
  }
  assert(a.n == b.n);
  HyperDual<C> r;
  r.n = a.n;
  r.v = a.v * b.v;
  for (int i = 0, k = 0; i < a.n; ++i) {
    r.g[i] = a.v * b.g[i] + b.v * a.g[i];
    for (int j = i; j < a.n; ++j, ++k) {
      r.h[k] = a.v * b.h[k] + b.v * a.h[k] + a.g[i] * b.g[j] + a.g[j] * b.g[i];
    }
  }
  return r;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator/(const HyperDual<C>& a, const HyperDual<C>& b) {
  if (b.n == 0) {
    HyperDual<C> r = a.apply(0.0, 1.0 / b.v, 0.0);
    r.v = a.v / b.v;
    return r;
  }
  // q = a/b: a = q·b, differentiated once and twice.
  HyperDual<C> q;
  q.n = b.n;
  q.v = a.v / b.v;
  const double inv = 1.0 / b.v;
  for (int i = 0; i < b.n; ++i) q.g[i] = ((a.n == 0 ? 0.0 : a.g[i]) - q.v * b.g[i]) * inv;
  for (int i = 0, k = 0; i < b.n; ++i) {
    for (int j = i; j < b.n; ++j, ++k) {
      q.h[k] = ((a.n == 0 ? 0.0 : a.h[k]) - q.v * b.h[k] - q.g[i] * b.g[j] - q.g[j] * b.g[i]) * inv;
    }
  }
  return q;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator+(const HyperDual<C>& a, double b) {
  return a + HyperDual<C>(b);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator+(double a, const HyperDual<C>& b) {
  return HyperDual<C>(a) + b;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator-(const HyperDual<C>& a, double b) {
  return a - HyperDual<C>(b);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator-(double a, const HyperDual<C>& b) {
  return HyperDual<C>(a) - b;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator*(const HyperDual<C>& a, double b) {
  return a * HyperDual<C>(b);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator*(double a, const HyperDual<C>& b) {
  return HyperDual<C>(a) * b;
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator/(const HyperDual<C>& a, double b) {
  return a / HyperDual<C>(b);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> operator/(double a, const HyperDual<C>& b) {
  return HyperDual<C>(a) / b;
}

template <int C>
LOCBENCH_HD_INLINE HyperDual<C> sin(const HyperDual<C>& a) {
  const double s = std::sin(a.v);
  return a.apply(s, std::cos(a.v), -s);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> cos(const HyperDual<C>& a) {
  const double c = std::cos(a.v);
  return a.apply(c, -std::sin(a.v), -c);
}
// sin and cos of one number with one evaluation of std::sin and std::cos (the same values).
template <int C>
LOCBENCH_HD_INLINE void sincos(const HyperDual<C>& a, HyperDual<C>& s, HyperDual<C>& c) {
  const double sv = std::sin(a.v), cv = std::cos(a.v);
  s = a.apply(sv, cv, -sv);
  c = a.apply(cv, -sv, -cv);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> exp(const HyperDual<C>& a) {
  const double e = std::exp(a.v);
  return a.apply(e, e, e);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> expm1(const HyperDual<C>& a) {
  const double e = std::exp(a.v);
  return a.apply(std::expm1(a.v), e, e);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> log(const HyperDual<C>& a) {
  return a.apply(std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> log1p(const HyperDual<C>& a) {
  const double d = 1.0 + a.v;
  return a.apply(std::log1p(a.v), 1.0 / d, -1.0 / (d * d));
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> sqrt(const HyperDual<C>& a) {
  const double r = std::sqrt(a.v);
  return a.apply(r, 0.5 / r, -0.25 / (r * a.v));
}
// atan2(y, x) through atan of the smaller ratio: atan(y/x) (+ a constant) where |x| ≥ |y|, else
// −atan(x/y) (+ a constant).
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> atan2(const HyperDual<C>& y, const HyperDual<C>& x) {
  const double angle = std::atan2(y.v, x.v);
  const bool by_x = std::abs(x.v) >= std::abs(y.v);
  const HyperDual<C> u = by_x ? y / x : x / y;
  const double q = 1.0 / (1.0 + u.v * u.v), sign = by_x ? 1.0 : -1.0;
  return u.apply(angle, sign * q, -sign * 2.0 * u.v * q * q);
}
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> abs(const HyperDual<C>& a) {
  return a.v < 0.0 ? -a : a;
}

// ψ(x) and ψ'(x) (digamma, trigamma) for x > 0: recurrence up to x ≥ 8, then the asymptotic
// series (relative error below 1e-13 there).
double digamma(double x);
double trigamma(double x);
// lgamma with its first two derivatives.
template <int C>
LOCBENCH_HD_INLINE HyperDual<C> lgamma(const HyperDual<C>& a) {
  return a.apply(std::lgamma(a.v), digamma(a.v), trigamma(a.v));
}

}  // namespace locbench::diagnosis

#pragma GCC diagnostic pop
