#pragma once
// Range-bearing landmark observations against ground truth: the model the landmark channel fits
// (landmark_channel.h) and that a filter can load from a report (`"models": {"landmark": …}`).
//
// An observation (t, id, z_r, z_b) of map landmark m = (m_x, m_y) from the true pose p = (x, y, θ)
// read at t − time_offset (TRUEPOS interpolated):
//   ρ = |m + δ − p|,  φ = atan2(m_y + δ_y − y, m_x + δ_x − x) − θ                (prediction)
//   z_r = s(φ)·ρ + range_bias + n_r,  s(φ) = range_scale + off_axis_linear·φ + off_axis·φ²   (model)
//   z_b = φ + bearing_bias + n_b
//   Var n_r = σ_r² + (range_noise_slope·ρ)²,  Var n_b = σ_b² + (bearing_noise_turn_slope·ω)²
// (ω the true turn rate at the observation: a camera's bearing blurs and jitters while turning)
// with δ = (position_error_dx, _dy) for the one landmark `position_error_id` (true position −
// surveyed position; δ = 0 for the others) and n_r, n_b independent: normal (dof = 0) or
// Student-t with `dof` degrees of freedom and those squared scales (heavy tails, outliers).
// Residuals are z − prediction, the bearing wrapped to [−π, π). SI: m, rad, s.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/angle.h"
#include "core/sensor_data.h"

namespace locbench::diagnosis {

// s(φ) = scale + linear·φ + quadratic·φ² with φ held within ±field_of_view (the model below; the
// filter's sensor model, pipelines/landmark_tracking.h, evaluates it the same way).
inline double off_axis_range_scale(double scale, double linear, double quadratic, double field_of_view, double phi) {
  const double p = std::clamp(phi, -field_of_view, field_of_view);
  return scale + (linear + quadratic * p) * p;
}

struct LandmarkModel {
  double range_scale = 1.0;  // [1]
  double range_bias = 0.0;   // [m]
  // How the range scale changes off the sensor's axis, s(φ) above (a camera that reads range from
  // a landmark's apparent size, with lens distortion towards the image's edges whose centre need
  // not be at bearing 0).
  double range_off_axis_linear = 0.0;  // [1/rad]
  double range_off_axis = 0.0;         // [1/rad²]
  // The largest |bearing| the sensor reported [rad]: s(φ) is held at its value there beyond it (a
  // twin's drifted pose can put a landmark outside the view the polynomial was fitted on).
  double field_of_view = kPi;
  double range_scale_at(double phi) const {
    return off_axis_range_scale(range_scale, range_off_axis_linear, range_off_axis, field_of_view, phi);
  }
  double bearing_bias = 0.0;              // [rad]
  double sigma_range = 0.05;              // σ_r [m]
  double sigma_bearing = 0.02;            // σ_b [rad]
  double range_noise_slope = 0.0;         // [m of σ per m of range]
  double bearing_noise_turn_slope = 0.0;  // [rad of σ per rad/s of turn rate]
  double dof = 0.0;                       // Student-t degrees of freedom; 0 = normal
  double time_offset = 0.0;               // observation logged time − true time [s]
  int position_error_id = -1;             // the landmark whose surveyed position is off; −1 = none
  double position_error_dx = 0.0;         // true − surveyed [m]
  double position_error_dy = 0.0;         // [m]
};
// Strict: an unknown key, a wrong type or a value out of range → UsageError naming the key.
void to_json(nlohmann::json& j, const LandmarkModel& m);
void from_json(const nlohmann::json& j, LandmarkModel& m);
void validate(const LandmarkModel& m);

// What the channel works on: the observations of mapped landmarks (others left out and counted).
struct LandmarkData {
  std::vector<LandmarkReading> readings;  // subjects in the map, in time order
  std::vector<int> landmark;              // per reading: its index in `map`
  std::vector<MapLandmark> map;
  std::vector<TruePose> truth;
  std::size_t unmapped = 0;         // observations of subjects not in the map (e.g. other robots)
  double reference_interval = 0.0;  // median TRUEPOS interval [s]
};
// Keeps the observations whose subject is in the map; sorts them by time.
LandmarkData make_landmark_data(const std::vector<LandmarkReading>& readings, const std::vector<MapLandmark>& map,
                                const std::vector<TruePose>& truth);

// The geometry of one observation at a time offset: the true pose and the nominal prediction.
struct LandmarkGeometry {
  bool valid = false;  // the truth covers t − offset
  double x = 0.0, y = 0.0, theta = 0.0;
  double rho = 0.0, phi = 0.0;  // nominal prediction (δ = 0) [m], [rad]
  double turn_rate = 0.0;       // true [rad/s], over ±0.05 s
};
std::vector<LandmarkGeometry> landmark_geometry(const LandmarkData& d, double time_offset);

struct LandmarkResidual {
  double range = 0.0, bearing = 0.0;          // z − prediction (scale, biases, δ applied)
  double var_range = 0.0, var_bearing = 0.0;  // the model's squared scales
  double rho = 0.0;                           // predicted range [m]
  double phi = 0.0;                           // predicted bearing (no bias) [rad]
  bool valid = false;
};
LandmarkResidual landmark_residual(const LandmarkData& d, std::size_t i, const LandmarkGeometry& g,
                                   const LandmarkModel& m);

// Negative log-likelihood of the observations `index` (all when empty). Observations whose shifted
// time leaves the truth count with the density's value at 0, so likelihoods stay comparable
// across offsets. `geometry` must be landmark_geometry(d, m.time_offset).
double landmark_nll(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry, const LandmarkModel& m,
                    const std::vector<std::size_t>& index);
// The same, computing the geometry.
double landmark_nll(const LandmarkData& d, const LandmarkModel& m, const std::vector<std::size_t>& index);

}  // namespace locbench::diagnosis
