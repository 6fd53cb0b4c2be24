#include "core/pose_measurement.h"

#include <cmath>

#include "core/angle.h"

namespace locbench {
namespace {

LinearizedMeasurement linearize_one(const CompassHeading& c, const Eigen::Vector3d& x) {
  LinearizedMeasurement m;  // eq. 3.28, 4.45
  m.z.resize(1);
  m.z(0) = c.heading;
  m.predicted.resize(1);
  m.predicted(0) = x(2);
  m.H.resize(1, 3);
  m.H << 0.0, 0.0, 1.0;
  m.R.resize(1, 1);
  m.R(0, 0) = c.variance;
  m.angular = {true, false};
  return m;
}

LinearizedMeasurement linearize_one(const LandmarkRangeBearing& l, const Eigen::Vector3d& x) {
  LinearizedMeasurement m;  // Probabilistic Robotics, Table 7.2
  const double dx = l.landmark_x - x(0), dy = l.landmark_y - x(1);
  const double q = dx * dx + dy * dy;
  const double r = std::sqrt(q);
  m.z.resize(2);
  m.z << l.range, l.bearing;
  m.predicted.resize(2);
  m.predicted << r, std::atan2(dy, dx) - x(2);
  m.H.resize(2, 3);
  if (q > 0.0) {
    m.H << -dx / r, -dy / r, 0.0, dy / q, -dx / q, -1.0;
  } else {  // on the landmark: no direction; the bearing still sees the heading
    m.H << 0.0, 0.0, 0.0, 0.0, 0.0, -1.0;
  }
  m.R.setZero(2, 2);
  m.R(0, 0) = l.range_variance;
  m.R(1, 1) = l.bearing_variance;
  m.angular = {false, true};
  return m;
}

}  // namespace

MeasurementVector LinearizedMeasurement::residual(const MeasurementVector* offset) const {
  MeasurementVector v(z.size());
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double h = offset ? predicted(i) + (*offset)(i) : predicted(i);
    v(i) = angular[static_cast<std::size_t>(i)] ? angle_diff(z(i), h) : z(i) - h;
  }
  return v;
}

LinearizedMeasurement linearize(const PoseMeasurement& m, const Eigen::Vector3d& x) {
  return std::visit([&](const auto& one) { return linearize_one(one, x); }, m);
}

MeasurementVector measurement_residual(const PoseMeasurement& m, const Eigen::Vector3d& x) {
  return linearize(m, x).residual();
}

}  // namespace locbench
