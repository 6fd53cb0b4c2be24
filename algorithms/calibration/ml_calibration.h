#pragma once
// Maximum-likelihood odometry calibration from any samples with a reference (calibration_data.h):
// the odometry parameters of the data's kind (calibration_model.h) and, when the references are
// a sensor's own displacements, the sensor's mounting pose (x, y, θ) jointly, as Censi et al.
// (IEEE T-RO 2013) do — with a covariance for every estimate. ML_CALIBRATION.md has the details.
//
// Estimator: the closed form (closed_form_calibration.h) gives the start; then a joint
// Levenberg–Marquardt minimisation (Ceres Solver, ml_calibration_solver.h) of Σ rᵢᵀ Σᵢ⁻¹ rᵢ over all free parameters,
// rᵢ = predicted − reference displacement, alternated with the ML estimate of the noise model's unknown variances (Σᵢ
// evaluated at the current parameters and held fixed within each solve). Covariance: the inverse Fisher information (Σ
// Jᵢᵀ Σᵢ⁻¹ Jᵢ)⁻¹ at the solution.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "algorithms/calibration/calibration_data.h"
#include "algorithms/calibration/calibration_model.h"
#include "algorithms/calibration/identifiability.h"

namespace locbench::calibration {

enum class NoiseModelKind {
  // Σᵢ = diag(σ_x², σ_y², σ_θ²) for every sample: the reference (e.g. a scan matcher) dominates
  // the noise. Censi et al.'s model; the σ are the residuals' root mean squares.
  kPerComponent,
  // Σᵢ = k²·Pᵢ + Qᵢ + diag(σ_t², σ_t², σ_r²): the odometry dominates. Pᵢ is the wheel noise
  // (variance k²|U| per wheel travel U, eq. 4.16) propagated through the sample's arcs, Qᵢ the
  // encoder quantization (ticks only), σ_t, σ_r the reference's own noise.
  kOdometryPropagated,
};

struct NoiseModelOptions {
  NoiseModelKind kind = NoiseModelKind::kOdometryPropagated;
  // Estimate the unknown variances by maximum likelihood (true), or use the values below.
  bool estimate = true;
  // kPerComponent: values when not estimated.
  double sigma_x = 1e-3;      // [m]
  double sigma_y = 1e-3;      // [m]
  double sigma_theta = 1e-3;  // [rad]
  // kOdometryPropagated: start (or fixed) values.
  double k = 0.005;                 // [√m]
  double sigma_translation = 1e-3;  // σ_t [m]
  double sigma_rotation = 1e-3;     // σ_r [rad]
  // Body and velocity kinds: track of the virtual differential drive that turns their
  // increments into wheel travel for Pᵢ [m].
  double virtual_track = 0.5;
};

// Censi et al.'s outlier rejection: `iterations` times, solve and then drop the samples whose
// translation residual ‖(Δx, Δy)‖ or rotation residual |Δθ| is above the (1 − fraction)
// quantile of its kind. Their solver's defaults are 4 iterations of 1 %. 0 = keep every sample.
struct OutlierOptions {
  int iterations = 0;
  double fraction = 0.01;
};

struct MlCalibrationOptions {
  // Sensor pose (only when the data's references are sensor displacements): estimate it, or
  // hold it at CalibrationData::nominal_sensor_pose.
  bool estimate_sensor_pose = true;
  // The third odometry parameter of the body and velocity kinds (rotation_per_distance,
  // rv_bias): estimated only when asked (the wheel kinds always estimate all three).
  bool estimate_rotation_per_distance = false;
  bool estimate_rotation_rate_bias = false;
  // Parameters held at their nominal values, by name (e.g. {"wheelbase"}).
  std::vector<std::string> fixed;
  NoiseModelOptions noise;
  OutlierOptions outliers;
  int max_iterations = 100;                  // Levenberg–Marquardt iterations per solve
  int noise_iterations = 30;                 // alternations of parameter solve and noise estimate
  double identifiability_tolerance = 1e-10;  // relative eigenvalue cutoff (identifiability.h)
};

struct CalibratedParameter {
  std::string name;
  double value = 0.0;
  double nominal = 0.0;
  double standard_error = 0.0;  // √ of the covariance diagonal; +∞ when not identifiable
  double closed_form = 0.0;     // the closed-form (two-step) value the solver started from
  bool identifiable = true;
  std::string reason;  // why not, from analyze_identifiability
};

struct MlCalibrationResult {
  OdometryInputKind kind = OdometryInputKind::kWheelTicks;
  // The estimated parameters, in the order odometry (three names of the kind), sensor.
  std::vector<CalibratedParameter> parameters;
  Eigen::MatrixXd covariance;             // of `parameters`, same order
  ModelParameters estimate;               // all six values (fixed ones at their nominal values)
  ModelParameters closed_form;            // the two-step estimate on the same samples
  IdentifiabilityReport identifiability;  // of the Fisher information at the solution

  // Noise model at the solution (kPerComponent: σ_x, σ_y, σ_θ; kOdometryPropagated: k, σ_t, σ_r).
  NoiseModelKind noise_kind = NoiseModelKind::kOdometryPropagated;
  Eigen::Vector3d noise = Eigen::Vector3d::Zero();

  double residual_rms_translation = 0.0;  // √mean(Δx² + Δy²) over the used samples [m]
  double residual_rms_rotation = 0.0;     // √mean(Δθ²) [rad]
  double chi2 = 0.0;                      // Σ rᵢᵀ Σᵢ⁻¹ rᵢ at the solution
  double dof = 0.0;                       // 3·used − free parameters
  double chi2_per_dof = 0.0;
  std::size_t samples_used = 0;
  std::size_t samples_rejected = 0;
  std::vector<bool> used;  // per input sample: false when rejected as an outlier
  int iterations = 0;      // Levenberg–Marquardt iterations, all solves together
  bool converged = false;

  // The parameter called `name`; throws std::out_of_range for an unknown or non-estimated one.
  const CalibratedParameter& parameter(const std::string& name) const;
  double value(const std::string& name) const { return parameter(name).value; }
};

// Throws std::invalid_argument for data without samples, non-finite samples, more free
// parameters than 3 × samples, an unknown name in `fixed`, or invalid options.
MlCalibrationResult calibrate_ml(const CalibrationData& data, const MlCalibrationOptions& options = {});

}  // namespace locbench::calibration
