#pragma once
// One pass of moments per run of the EAP matcher: the run's direction check, the
// match's least-squares line and every step of its trim read the same sums, with the
// direction taken from the 2×2 scatter matrix's eigenvector instead of atan2/cos/sin.
// The line is the orthogonal least-squares line of line_fit.h (the same quantity; it differs
// from fit_line's by rounding only, ≲ 1e-12 m and rad — measured in eap_equivalence_test).
#include <cmath>
#include <cstddef>

#include "algorithms/laser/line_fit.h"
#include "core/angle.h"

namespace locbench::laser::detail {

// Sums over points q = p − o about a fixed origin o (the segment's midpoint: small |q| keeps
// the one-pass covariance free of cancellation).
struct Moments {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;

  void add(double qx, double qy) {
    n += 1.0;
    sx += qx;
    sy += qy;
    sxx += qx * qx;
    sxy += qx * qy;
    syy += qy * qy;
  }
  void remove(double qx, double qy) {
    n -= 1.0;
    sx -= qx;
    sy -= qy;
    sxx -= qx * qx;
    sxy -= qx * qy;
    syy -= qy * qy;
  }
  Moments& operator+=(const Moments& o) {
    n += o.n;
    sx += o.sx;
    sy += o.sy;
    sxx += o.sxx;
    sxy += o.sxy;
    syy += o.syy;
    return *this;
  }
};

// Mean (about the moments' origin) and the unit direction of largest spread, with fit_line's
// sign convention: direction (cos φ, sin φ) for φ ∈ [−π/2, π/2], i.e. x ≥ 0.
struct PrincipalAxis {
  double mean_x = 0.0, mean_y = 0.0;
  double ux = 1.0, uy = 0.0;
};

inline PrincipalAxis principal_axis(const Moments& m) {
  PrincipalAxis a;
  if (!(m.n > 0.0)) return a;
  a.mean_x = m.sx / m.n;
  a.mean_y = m.sy / m.n;
  // Centred scatter [[sxx, sxy], [sxy, syy]]; eigenvalue λ = (sxx + syy)/2 + s,
  // s = √(h² + sxy²), h = (sxx − syy)/2. Eigenvector (λ − syy, sxy) = (h + s, sxy) when h ≥ 0,
  // else (sxy, λ − sxx) = (sxy, s − h): both free of cancellation.
  const double sxx = m.sxx - m.sx * a.mean_x;
  const double syy = m.syy - m.sy * a.mean_y;
  const double sxy = m.sxy - m.sx * a.mean_y;
  const double h = 0.5 * (sxx - syy);
  const double s = std::sqrt(h * h + sxy * sxy);
  if (!(s > 0.0)) return a;  // isotropic or a single point: fit_line's φ = 0
  double vx = 0.0, vy = 0.0;
  if (h >= 0.0) {
    vx = h + s;
    vy = sxy;
  } else {
    vx = sxy;
    vy = s - h;
    if (std::signbit(vx)) {  // x ≥ 0; for x = ±0 the sign of sxy decides, as in atan2
      vx = -vx;
      vy = -vy;
    }
  }
  const double inv = 1.0 / std::sqrt(vx * vx + vy * vy);
  a.ux = vx * inv;
  a.uy = vy * inv;
  return a;
}

// The LineFit of line_fit.h from the moments about (ox, oy), their principal axis, the sum of
// squared perpendicular residuals `ss`, and the first and last point (beam order).
inline LineFit line_fit_from(const Moments& m, const PrincipalAxis& a, double ox, double oy, double ss,
                             const Eigen::Vector2d& first, const Eigen::Vector2d& last) {
  LineFit f;
  f.count = static_cast<std::size_t>(m.n);
  f.centroid = {ox + a.mean_x, oy + a.mean_y};
  f.direction = {a.ux, a.uy};
  Eigen::Vector2d n(-a.uy, a.ux);
  double rho = n.dot(f.centroid);
  if (rho < 0) {
    n = -n;
    rho = -rho;
  }
  f.line.rho = rho;
  f.line.beta = wrap_angle(std::atan2(n.y(), n.x()));
  f.rms = std::sqrt(ss / m.n);
  f.first = f.centroid + f.direction * f.direction.dot(first - f.centroid);
  f.last = f.centroid + f.direction * f.direction.dot(last - f.centroid);
  return f;
}

}  // namespace locbench::laser::detail
