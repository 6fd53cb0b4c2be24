#pragma once
// The absolute measurements a pose EKF corrects with, through one interface (state [x, y, θ]):
// - the compass heading, z = θ + v (eq. 3.28, 4.45): h(x) = θ, H = [0 0 1];
// - the range and bearing to a landmark of known position and identity (Probabilistic Robotics,
//   Table 7.2, known correspondence): with Δ = m − (x, y) and q = |Δ|²,
//     h(x) = [√q, atan2(Δy, Δx) − θ],   H = [[−Δx/√q, −Δy/√q, 0], [Δy/q, −Δx/q, −1]].
// A measurement carries its own noise R; linearize() evaluates h and H at a state. Angular
// components (heading, bearing) of every residual are wrapped to [−π, π). SI units.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <variant>

namespace locbench {

struct CompassHeading {
  double heading = 0.0;   // [rad], counter-clockwise from the world x axis
  double variance = 0.0;  // R [rad²]
};

struct LandmarkRangeBearing {
  double range = 0.0;                         // [m]
  double bearing = 0.0;                       // [rad] in the robot frame (x forward, y left)
  double landmark_x = 0.0, landmark_y = 0.0;  // the landmark's map position [m]
  double range_variance = 0.0;                // R = diag(σ_r², σ_φ²) [m², rad²]
  double bearing_variance = 0.0;
};

using PoseMeasurement = std::variant<CompassHeading, LandmarkRangeBearing>;
// The number of measurement kinds (adaptive filters keep noise statistics per kind).
inline constexpr std::size_t kMeasurementKinds = std::variant_size_v<PoseMeasurement>;

// At most two components: fixed-capacity Eigen types, no allocation per update.
using MeasurementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1>;
using MeasurementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 2>;
using MeasurementJacobian = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 2, 3>;
using MeasurementGain = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 2>;

struct LinearizedMeasurement {
  MeasurementVector z;          // measured
  MeasurementVector predicted;  // h(x̂)
  MeasurementJacobian H;        // ∂h/∂x at x̂
  MeasurementMatrix R;          // the measurement's own noise covariance
  std::array<bool, 2> angular{};

  // z − (h(x̂) + offset), angular components wrapped; offset (e.g. the Sage–Husa mean r̂) may
  // be null.
  MeasurementVector residual(const MeasurementVector* offset = nullptr) const;
};

LinearizedMeasurement linearize(const PoseMeasurement& m, const Eigen::Vector3d& x);
// z − h(x) at any state (e.g. the posterior), angular components wrapped.
MeasurementVector measurement_residual(const PoseMeasurement& m, const Eigen::Vector3d& x);

}  // namespace locbench
