#include "algorithms/calibration/calibration_model.h"

#include <array>
#include <cmath>

#include "core/angle.h"

namespace locbench::calibration {
namespace {

// sin(θ)/θ, (1 − cos θ)/θ and their derivatives, with series near θ = 0.
struct ArcTerms {
  double s = 1.0, c = 0.0, ds = 0.0, dc = 0.5;
};
ArcTerms arc_terms(double th) {
  ArcTerms t;
  if (std::abs(th) < 1e-4) {
    const double th2 = th * th;
    t.s = 1.0 - th2 / 6.0;
    t.c = th / 2.0 - th * th2 / 24.0;
    t.ds = -th / 3.0 + th * th2 / 30.0;
    t.dc = 0.5 - th2 / 8.0;
  } else {
    const double sn = std::sin(th), cs = std::cos(th);
    t.s = sn / th;
    t.c = (1.0 - cs) / th;
    t.ds = (th * cs - sn) / (th * th);
    t.dc = (th * sn - (1.0 - cs)) / (th * th);
  }
  return t;
}

// Wheel travel (U_L, U_R) of an increment and the track that turns it into a rotation.
struct WheelTravel {
  double left = 0.0, right = 0.0, track = 1.0;
};
WheelTravel wheel_travel(const CalibrationData& data, const OdometryIncrement& inc, const Eigen::Vector3d& q,
                         double virtual_track) {
  switch (data.kind) {
    case OdometryInputKind::kWheelTicks:
      return {q(0) * data.meters_per_tick_left * inc.first, q(1) * data.meters_per_tick_right * inc.second, q(2)};
    case OdometryInputKind::kWheelAngles: return {q(0) * inc.first, q(1) * inc.second, q(2)};
    case OdometryInputKind::kBodyIncrements:
    case OdometryInputKind::kVelocityIntegrals: break;
  }
  const ArcIncrement a = arc_of(data, inc, q);
  return {a.distance - 0.5 * virtual_track * a.rotation, a.distance + 0.5 * virtual_track * a.rotation, virtual_track};
}

// Small matrices as plain arrays: the code below runs per increment and per solver evaluation,
// and Eigen's fixed-size expressions cost ~10× more than the arithmetic in the unoptimised
// (-O0, sanitized) test build.
using Mat3 = std::array<std::array<double, 3>, 3>;

// F·P·Fᵀ.
Mat3 congruence(const Mat3& F, const Mat3& P) {
  Mat3 FP{}, out{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      FP[i][j] = F[i][0] * P[0][j] + F[i][1] * P[1][j] + F[i][2] * P[2][j];
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      out[i][j] = FP[i][0] * F[j][0] + FP[i][1] * F[j][1] + FP[i][2] * F[j][2];
    }
  }
  return out;
}

// P += w·f·fᵀ.
void add_outer(Mat3& P, const std::array<double, 3>& f, double w) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) P[i][j] += w * f[i] * f[j];
  }
}

Eigen::Matrix3d to_eigen(const Mat3& m) {
  Eigen::Matrix3d out;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out(i, j) = m[i][j];
  }
  return out;
}

// ∂(ΔD, Δθ)/∂q of arc_of (rows ΔD, Δθ): linear in the scales, Δθ ∝ 1/B in the wheelbase.
using ArcJacobian = std::array<std::array<double, 3>, 2>;
ArcJacobian arc_jacobian(const CalibrationData& data, const OdometryIncrement& inc, const Eigen::Vector3d& q) {
  switch (data.kind) {
    case OdometryInputKind::kWheelTicks:
    case OdometryInputKind::kWheelAngles: {
      const bool ticks = data.kind == OdometryInputKind::kWheelTicks;
      const double ul = (ticks ? data.meters_per_tick_left : 1.0) * inc.first;    // ∂U_L/∂q₀
      const double ur = (ticks ? data.meters_per_tick_right : 1.0) * inc.second;  // ∂U_R/∂q₁
      const double b = q(2), rotation = (q(1) * ur - q(0) * ul) / b;
      return {{{0.5 * ul, 0.5 * ur, 0.0}, {-ul / b, ur / b, -rotation / b}}};
    }
    case OdometryInputKind::kBodyIncrements: return {{{inc.first, 0.0, 0.0}, {0.0, inc.second, inc.first}}};
    case OdometryInputKind::kVelocityIntegrals: return {{{inc.first, 0.0, 0.0}, {0.0, inc.second, inc.dt}}};
  }
  return {};
}

// The robot displacement o over a sample in plain doubles (Pose2 would wrap the heading at every
// step; only the final one is wrapped) and, when `d_odometry` is given, ∂(o_x, o_y, o_θ)/∂q,
// carried through the composition: o ← o ∘ a gives ∂o ← F_p·∂o + R·A·∂(ΔD, Δθ)/∂q
// (F_p, R, A as in odometry_noise_shape).
Pose2 compose_arcs(const CalibrationData& data, const CalibrationSample& sample, const Eigen::Vector3d& odometry,
                   Mat3* d_odometry) {
  double x = 0.0, y = 0.0, th = 0.0;
  Mat3 d{};
  for (const OdometryIncrement& inc : sample.increments) {
    const ArcIncrement a = arc_of(data, inc, odometry);
    const ArcTerms t = arc_terms(a.rotation);
    const double ax = a.distance * t.s, ay = a.distance * t.c;
    const double c = std::cos(th), s = std::sin(th);
    if (d_odometry != nullptr) {
      const ArcJacobian dq = arc_jacobian(data, inc, odometry);
      const double fx = -s * ax - c * ay, fy = c * ax - s * ay;  // ∂(x, y)/∂θ of o ∘ a
      for (int j = 0; j < 3; ++j) {
        const double dax = t.s * dq[0][j] + a.distance * t.ds * dq[1][j];
        const double day = t.c * dq[0][j] + a.distance * t.dc * dq[1][j];
        const double dth = d[2][j];
        d[0][j] += c * dax - s * day + fx * dth;
        d[1][j] += s * dax + c * day + fy * dth;
        d[2][j] += dq[1][j];
      }
    }
    x += c * ax - s * ay;
    y += s * ax + c * ay;
    th += a.rotation;
  }
  if (d_odometry != nullptr) *d_odometry = d;
  return {x, y, th};
}

// ∂(ℓ⁻¹ ∘ o ∘ ℓ)/∂o for a robot displacement with heading `o_theta`: with
// s_t = R(−ℓθ)(o_t + (R(oθ) − I)ℓ_t), s_θ = o_θ.
Mat3 sensor_frame_jacobian(const Pose2& l, double o_theta) {
  const double cl = std::cos(l.theta), sl = std::sin(l.theta);
  const double co = std::cos(o_theta), so = std::sin(o_theta);
  const double rx = -so * l.x - co * l.y, ry = co * l.x - so * l.y;  // ∂(R(oθ)ℓ_t)/∂oθ
  // R(−ℓθ) = [[cl, sl], [−sl, cl]].
  return {{{cl, sl, cl * rx + sl * ry}, {-sl, cl, -sl * rx + cl * ry}, {0.0, 0.0, 1.0}}};
}

// ∂(ℓ⁻¹ ∘ o ∘ ℓ)/∂(ℓ_x, ℓ_y, ℓ_θ): R(−ℓθ)(R(oθ) − I) for the position, ∂R(−ℓθ)/∂ℓθ =
// [[−sl, cl], [−cl, −sl]] applied to v = o_t + (R(oθ) − I)ℓ_t for the angle; the heading
// s_θ = o_θ does not depend on ℓ.
Mat3 sensor_mount_jacobian(const Pose2& l, const Pose2& o) {
  const double cl = std::cos(l.theta), sl = std::sin(l.theta);
  // R(oθ) − I = [[cm, −so], [so, cm]].
  const double cm = std::cos(o.theta) - 1.0, so = std::sin(o.theta);
  const double vx = o.x + cm * l.x - so * l.y, vy = o.y + so * l.x + cm * l.y;
  return {{{cl * cm + sl * so, -cl * so + sl * cm, -sl * vx + cl * vy},
           {-sl * cm + cl * so, sl * so + cl * cm, -cl * vx - sl * vy},
           {0.0, 0.0, 0.0}}};
}

// The residual and, when `jacobian` is given, its exact derivative (one code path for both, so
// the residual is the same number either way).
Eigen::Vector3d residual_of(const CalibrationData& data, const CalibrationSample& sample, const ModelParameters& p,
                            Eigen::Matrix<double, 3, 6>* jacobian) {
  Mat3 d_odometry{};
  const Pose2 o = compose_arcs(data, sample, p.odometry, jacobian != nullptr ? &d_odometry : nullptr);
  Pose2 e = o;
  Mat3 d_sensor{};
  if (data.sensor_reference) {
    e = p.sensor.inverse() * o * p.sensor;
    if (jacobian != nullptr) {
      const Mat3 G = sensor_frame_jacobian(p.sensor, o.theta);
      Mat3 Gd{};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          Gd[i][j] = G[i][0] * d_odometry[0][j] + G[i][1] * d_odometry[1][j] + G[i][2] * d_odometry[2][j];
        }
      }
      d_odometry = Gd;
      d_sensor = sensor_mount_jacobian(p.sensor, o);
    }
  }
  if (jacobian != nullptr) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        (*jacobian)(i, j) = d_odometry[i][j];
        (*jacobian)(i, j + 3) = d_sensor[i][j];
      }
    }
  }
  // The wrap of the angle residual has derivative 1 (away from ±π, where it jumps).
  return {e.x - sample.reference.x, e.y - sample.reference.y, angle_diff(e.theta, sample.reference.theta)};
}

}  // namespace

std::array<std::string, 3> odometry_parameter_names(OdometryInputKind kind) {
  switch (kind) {
    case OdometryInputKind::kWheelTicks: return {"left_scale", "right_scale", "wheelbase"};
    case OdometryInputKind::kWheelAngles: return {"r_L", "r_R", "b"};
    case OdometryInputKind::kBodyIncrements: return {"translation_scale", "rotation_scale", "rotation_per_distance"};
    case OdometryInputKind::kVelocityIntegrals: return {"tv_scale", "rv_scale", "rv_bias"};
  }
  return {"p0", "p1", "p2"};
}

std::array<std::string, 3> sensor_parameter_names() { return {"sensor_x", "sensor_y", "sensor_theta"}; }

Eigen::Matrix<double, 6, 1> ModelParameters::vector() const {
  Eigen::Matrix<double, 6, 1> v;
  v << odometry, sensor.x, sensor.y, sensor.theta;
  return v;
}

ModelParameters ModelParameters::from_vector(const Eigen::Matrix<double, 6, 1>& v) {
  ModelParameters p;
  p.odometry = v.head<3>();
  p.sensor = Pose2(v(3), v(4), v(5));
  return p;
}

ModelParameters nominal_parameters(const CalibrationData& data) {
  ModelParameters p;
  p.odometry = data.nominal;
  p.sensor = data.nominal_sensor_pose;
  return p;
}

ArcIncrement arc_of(const CalibrationData& data, const OdometryIncrement& inc, const Eigen::Vector3d& q) {
  switch (data.kind) {
    case OdometryInputKind::kWheelTicks:
    case OdometryInputKind::kWheelAngles: {
      // ΔD = (U_L + U_R)/2, Δθ = (U_R − U_L)/B (eq. 1.1, 1.2).
      const WheelTravel u = wheel_travel(data, inc, q, 1.0);
      return {0.5 * (u.left + u.right), (u.right - u.left) / u.track};
    }
    case OdometryInputKind::kBodyIncrements: return {q(0) * inc.first, q(1) * inc.second + q(2) * inc.first};
    case OdometryInputKind::kVelocityIntegrals: return {q(0) * inc.first, q(1) * inc.second + q(2) * inc.dt};
  }
  return {};
}

Pose2 arc_displacement(double distance, double rotation) {
  const ArcTerms t = arc_terms(rotation);
  return {distance * t.s, distance * t.c, rotation};
}

Pose2 predict_robot_displacement(const CalibrationData& data, const CalibrationSample& sample,
                                 const Eigen::Vector3d& odometry) {
  return compose_arcs(data, sample, odometry, nullptr);
}

Pose2 predict_reference(const CalibrationData& data, const CalibrationSample& sample, const ModelParameters& p) {
  const Pose2 o = predict_robot_displacement(data, sample, p.odometry);
  if (!data.sensor_reference) return o;
  return p.sensor.inverse() * o * p.sensor;
}

Eigen::Vector3d reference_residual(const CalibrationData& data, const CalibrationSample& sample,
                                   const ModelParameters& p) {
  return residual_of(data, sample, p, nullptr);
}

ResidualWithJacobian reference_residual_with_jacobian(const CalibrationData& data, const CalibrationSample& sample,
                                                      const ModelParameters& p) {
  ResidualWithJacobian out;
  out.residual = residual_of(data, sample, p, &out.jacobian);
  return out;
}

NoiseShape odometry_noise_shape(const CalibrationData& data, const CalibrationSample& sample, const ModelParameters& p,
                                double virtual_track) {
  Mat3 per_k2{}, quantization{};
  double th = 0.0;
  const std::size_t n = sample.increments.size();
  for (std::size_t k = 0; k < n; ++k) {
    const OdometryIncrement& inc = sample.increments[k];
    const WheelTravel u = wheel_travel(data, inc, p.odometry, virtual_track);
    const double dist = 0.5 * (u.left + u.right), rot = (u.right - u.left) / u.track;
    const ArcTerms t = arc_terms(rot);
    const double ax = dist * t.s, ay = dist * t.c;
    const double c = std::cos(th), s = std::sin(th);
    // F_p = ∂(p ∘ a)/∂p, R = ∂(p ∘ a)/∂a, A = ∂a/∂(ΔD, Δθ), B = ∂(ΔD, Δθ)/∂(U_L, U_R);
    // f_L, f_R = the columns of R·A·B.
    const Mat3 Fp{{{1.0, 0.0, -s * ax - c * ay}, {0.0, 1.0, c * ax - s * ay}, {0.0, 0.0, 1.0}}};
    auto column = [&](double d_distance, double d_rotation) {
      const double bx = t.s * d_distance + dist * t.ds * d_rotation;
      const double by = t.c * d_distance + dist * t.dc * d_rotation;
      return std::array<double, 3>{c * bx - s * by, s * bx + c * by, d_rotation};
    };
    const std::array<double, 3> fl = column(0.5, -1.0 / u.track), fr = column(0.5, 1.0 / u.track);
    per_k2 = congruence(Fp, per_k2);
    add_outer(per_k2, fl, std::abs(u.left));
    add_outer(per_k2, fr, std::abs(u.right));
    quantization = congruence(Fp, quantization);
    if (data.kind == OdometryInputKind::kWheelTicks && data.quantized_ticks && (k == 0 || k + 1 == n)) {
      // e_start on the first increment, e_end on the last, C²/12 each (uniform remainders).
      const double cl = p.odometry(0) * data.meters_per_tick_left;
      const double cr = p.odometry(1) * data.meters_per_tick_right;
      const double share = (n == 1) ? 2.0 : 1.0;
      add_outer(quantization, fl, share * cl * cl / 12.0);
      add_outer(quantization, fr, share * cr * cr / 12.0);
    }
    th += rot;
  }
  if (data.sensor_reference) {
    // s = ℓ⁻¹ ∘ o ∘ ℓ, linearised in o.
    const Mat3 G = sensor_frame_jacobian(p.sensor, th);
    per_k2 = congruence(G, per_k2);
    quantization = congruence(G, quantization);
  }
  NoiseShape out;
  out.per_k2 = to_eigen(per_k2);
  out.quantization = to_eigen(quantization);
  return out;
}

}  // namespace locbench::calibration
