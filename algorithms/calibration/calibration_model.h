#pragma once
// The measurement model of the ML odometry calibration: parameters per input kind, the predicted
// displacement of a sample (robot or sensor frame), and the odometry-noise shape used by the
// propagated noise model. See ML_CALIBRATION.md.
//
// Per increment the odometry gives a body increment (ΔD, Δθ) (eq. 1.1–1.2 for wheels, a scaled
// arc for the body kinds) integrated along a circular arc — the exact form of eq. 1.3 for
// constant wheel speeds over the increment (Censi et al. 2013, eq. 5):
//   x = ΔD·sin(Δθ)/Δθ,  y = ΔD·(1 − cos Δθ)/Δθ,  θ = Δθ.
// With a sensor mounted at ℓ the reference is ℓ⁻¹ ∘ o ∘ ℓ (o the robot displacement).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "core/pose2.h"

namespace locbench::calibration {

// Names of the three odometry parameters of a kind, in the order of CalibrationData::nominal:
// kWheelTicks: left_scale, right_scale, wheelbase; kWheelAngles: r_L, r_R, b;
// kBodyIncrements: translation_scale, rotation_scale, rotation_per_distance;
// kVelocityIntegrals: tv_scale, rv_scale, rv_bias.
std::array<std::string, 3> odometry_parameter_names(OdometryInputKind kind);
// Names of the sensor mounting pose parameters: sensor_x, sensor_y, sensor_theta.
std::array<std::string, 3> sensor_parameter_names();

// The full parameter set of the model.
struct ModelParameters {
  Eigen::Vector3d odometry = Eigen::Vector3d(1.0, 1.0, 0.0);
  Pose2 sensor;  // used only when the data's references are sensor displacements

  // (odometry, sensor x, y, θ) as one 6-vector, and back (θ unwrapped on the way in).
  Eigen::Matrix<double, 6, 1> vector() const;
  static ModelParameters from_vector(const Eigen::Matrix<double, 6, 1>& v);
};

// The data's uncalibrated parameters: its nominal odometry values and nominal sensor pose.
ModelParameters nominal_parameters(const CalibrationData& data);

// Body increment (ΔD [m], Δθ [rad]) of one odometry increment under `odometry` parameters.
struct ArcIncrement {
  double distance = 0.0;
  double rotation = 0.0;
};
ArcIncrement arc_of(const CalibrationData& data, const OdometryIncrement& inc, const Eigen::Vector3d& odometry);

// The displacement of a circular arc of length ΔD turning by Δθ (formula above).
Pose2 arc_displacement(double distance, double rotation);

// Robot displacement over a sample: the arcs of its increments composed in order.
Pose2 predict_robot_displacement(const CalibrationData& data, const CalibrationSample& sample,
                                 const Eigen::Vector3d& odometry);

// What the sample's reference should be under `p`: the robot displacement o, or ℓ⁻¹ ∘ o ∘ ℓ.
Pose2 predict_reference(const CalibrationData& data, const CalibrationSample& sample, const ModelParameters& p);

// Residual predicted − reference: (Δx, Δy, wrapped Δθ), in the reference's start frame.
Eigen::Vector3d reference_residual(const CalibrationData& data, const CalibrationSample& sample,
                                   const ModelParameters& p);

// The residual with its exact Jacobian ∂r/∂(odometry, sensor x, y, θ) (3 × 6, the order of
// ModelParameters::vector()): the arcs' derivatives carried through the composition, then the
// sensor conjugation's. The residual is the same number reference_residual gives. Columns of the
// sensor are zero when the references are robot displacements.
struct ResidualWithJacobian {
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 6> jacobian = Eigen::Matrix<double, 3, 6>::Zero();
};
ResidualWithJacobian reference_residual_with_jacobian(const CalibrationData& data, const CalibrationSample& sample,
                                                      const ModelParameters& p);

// Covariance shape of a sample's predicted reference under wheel noise (eq. 4.16: each wheel's
// travel U has variance k²|U|), propagated through the arcs (slides: Σ' = F_p Σ F_pᵀ +
// F_Δ Σ_Δ F_Δᵀ) and into the sensor frame:
// - `per_k2`: the covariance per unit k² [m];
// - `quantization`: for quantized kWheelTicks, the encoder quantization of the sample
// (eq. 4.12–4.21:
//   the travel measured over an interval is off by e_start − e_end, variance C²/6 per wheel,
//   put half on the first and half on the last increment); zero for the other kinds.
// The body and velocity kinds have no wheels: their increments are mapped to a virtual
// differential drive of track `virtual_track` [m] (U_L,R = ΔD ∓ track·Δθ/2).
struct NoiseShape {
  Eigen::Matrix3d per_k2 = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d quantization = Eigen::Matrix3d::Zero();
};
NoiseShape odometry_noise_shape(const CalibrationData& data, const CalibrationSample& sample, const ModelParameters& p,
                                double virtual_track);

}  // namespace locbench::calibration
