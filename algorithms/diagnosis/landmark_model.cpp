#include "algorithms/diagnosis/landmark_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "algorithms/diagnosis/motion_windows.h"
#include "core/angle.h"
#include "core/errors.h"
#include "core/option_fields.h"
#include "core/units.h"

namespace locbench::diagnosis {

// LandmarkModel's fields, stated once (landmark_model.h gives the equations).
template <class V>
void visit_fields(V& v, LandmarkModel& m) {
  v.field("range_scale", m.range_scale, "", positive(),
          "z_r = (range_scale + off_axis_linear·φ + off_axis·φ²)·ρ + range_bias + n_r");
  v.field("range_off_axis_per_rad", m.range_off_axis_linear, "1/rad", any_finite(),
          "the range scale's change with the bearing φ (off the sensor's axis)");
  v.field("range_off_axis_per_rad2", m.range_off_axis, "1/rad²", any_finite(),
          "the range scale's change with the squared bearing φ²");
  v.field("field_of_view_rad", m.field_of_view, "rad", positive(),
          "the largest |bearing| reported; the range scale is held at its value there beyond it");
  v.field("range_bias_m", m.range_bias, "m", any_finite(), "added to every range");
  v.field("bearing_bias_rad", m.bearing_bias, "rad", any_finite(), "added to every bearing");
  v.field("sigma_range_m", m.sigma_range, "m", non_negative(), "σ_r: range noise at range 0 (0 with a slope > 0)");
  v.field("sigma_bearing_rad", m.sigma_bearing, "rad", positive(), "σ_b: bearing noise");
  v.field("range_noise_slope", m.range_noise_slope, "m/m", non_negative(),
          "range noise grows with range: Var n_r = σ_r² + (slope·ρ)²");
  v.field("bearing_noise_turn_slope_s", m.bearing_noise_turn_slope, "s", non_negative(),
          "bearing noise grows with the turn rate ω: Var n_b = σ_b² + (slope·ω)²");
  v.field("dof", m.dof, "", non_negative(), "Student-t degrees of freedom of both noises; 0 = normal");
  v.field("time_offset_s", m.time_offset, "s", closed(-10.0, 10.0), "observation logged time − true time");
  v.field("position_error_id", m.position_error_id, "", at_least(-1),
          "landmark whose surveyed position is off; -1 none");
  v.field("position_error_dx_m", m.position_error_dx, "m", any_finite(), "its true − surveyed x");
  v.field("position_error_dy_m", m.position_error_dy, "m", any_finite(), "its true − surveyed y");
}

void validate(const LandmarkModel& m) { validate_fields(m, "LandmarkModel"); }

LOCBENCH_OPTIONS_JSON(LandmarkModel)

LandmarkData make_landmark_data(const std::vector<LandmarkReading>& readings, const std::vector<MapLandmark>& map,
                                const std::vector<TruePose>& truth) {
  LandmarkData d;
  d.map = map;
  d.truth = truth;
  std::map<int, int> index;
  for (std::size_t k = 0; k < map.size(); ++k) index[map[k].id] = static_cast<int>(k);
  std::vector<std::pair<LandmarkReading, int>> kept;
  for (const auto& r : readings) {
    const auto it = index.find(r.subject);
    if (it == index.end() || !std::isfinite(r.range) || !std::isfinite(r.bearing)) {
      ++d.unmapped;
      continue;
    }
    kept.emplace_back(r, it->second);
  }
  std::stable_sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) { return a.first.t < b.first.t; });
  for (const auto& [r, k] : kept) {
    d.readings.push_back(r);
    d.landmark.push_back(k);
  }
  std::vector<double> dt;
  for (std::size_t k = 1; k < truth.size(); ++k) dt.push_back(truth[k].t - truth[k - 1].t);
  if (!dt.empty()) {
    std::nth_element(dt.begin(), dt.begin() + static_cast<long>(dt.size() / 2), dt.end());
    d.reference_interval = dt[dt.size() / 2];
  }
  return d;
}

std::vector<LandmarkGeometry> landmark_geometry(const LandmarkData& d, double time_offset) {
  std::vector<LandmarkGeometry> out(d.readings.size());
  for_each_truth_sample(d.truth, d.readings, time_offset, [&](std::size_t i, const TruthSample& s) {
    LandmarkGeometry& g = out[i];
    const MapLandmark& m = d.map[static_cast<std::size_t>(d.landmark[i])];
    const Pose2& p = s.pose;
    g.valid = true;
    g.x = p.x;
    g.y = p.y;
    g.theta = p.theta;
    g.rho = std::hypot(m.x - p.x, m.y - p.y);
    g.phi = wrap_angle(std::atan2(m.y - p.y, m.x - p.x) - p.theta);
    g.turn_rate = s.turn_rate;
  });
  return out;
}

LandmarkResidual landmark_residual(const LandmarkData& d, std::size_t i, const LandmarkGeometry& g,
                                   const LandmarkModel& m) {
  LandmarkResidual r;
  if (!g.valid) return r;
  double rho = g.rho, phi = g.phi;
  const MapLandmark& lm = d.map[static_cast<std::size_t>(d.landmark[i])];
  if (lm.id == m.position_error_id) {
    const double mx = lm.x + m.position_error_dx, my = lm.y + m.position_error_dy;
    rho = std::hypot(mx - g.x, my - g.y);
    phi = std::atan2(my - g.y, mx - g.x) - g.theta;
  }
  r.valid = true;
  r.rho = rho;
  r.phi = wrap_angle(phi);
  r.range = d.readings[i].range - (m.range_scale_at(r.phi) * rho + m.range_bias);
  r.bearing = wrap_angle(d.readings[i].bearing - phi - m.bearing_bias);
  const double s = m.range_noise_slope * rho;
  r.var_range = m.sigma_range * m.sigma_range + s * s;
  const double sb = m.bearing_noise_turn_slope * g.turn_rate;
  r.var_bearing = m.sigma_bearing * m.sigma_bearing + sb * sb;
  return r;
}

namespace {

// Log-density of a residual r with squared scale v (log v given): normal (dof = 0) or Student-t.
struct LandmarkDensity {
  explicit LandmarkDensity(double nu)
      : dof(nu),
        constant(nu > 0.0 ? std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) - 0.5 * std::log(nu * kPi)
                          : -0.5 * std::log(2.0 * kPi)) {}
  double operator()(double r, double v, double log_v) const {
    if (!(dof > 0.0)) return constant - 0.5 * (r * r / v + log_v);
    return constant - 0.5 * log_v - 0.5 * (dof + 1.0) * std::log1p(r * r / (dof * v));
  }
  double dof, constant;
};

}  // namespace

double landmark_nll(const LandmarkData& d, const std::vector<LandmarkGeometry>& geometry, const LandmarkModel& m,
                    const std::vector<std::size_t>& index) {
  const bool range_noise = m.sigma_range > 0.0 || (m.sigma_range == 0.0 && m.range_noise_slope > 0.0);
  if (!range_noise || !(m.sigma_bearing > 0.0) || !(m.range_scale > 0.0) || m.dof < 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  const LandmarkDensity density(m.dof);
  const double v_r0 = std::max(m.sigma_range * m.sigma_range, 1e-12), v_b = m.sigma_bearing * m.sigma_bearing;
  const double log_v_r0 = std::log(v_r0), log_v_b = std::log(v_b);
  const bool growing = m.range_noise_slope != 0.0;
  const bool turning = m.bearing_noise_turn_slope != 0.0;
  const std::size_t n = index.empty() ? d.readings.size() : index.size();
  double nll = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = index.empty() ? k : index[k];
    const LandmarkResidual r = landmark_residual(d, i, geometry[i], m);
    if (!r.valid) {
      nll -= density(0.0, v_r0, log_v_r0) + density(0.0, v_b, log_v_b);
      continue;
    }
    nll -= density(r.range, r.var_range, growing ? std::log(r.var_range) : log_v_r0) +
           density(r.bearing, r.var_bearing, turning ? std::log(r.var_bearing) : log_v_b);
  }
  return nll;
}

double landmark_nll(const LandmarkData& d, const LandmarkModel& m, const std::vector<std::size_t>& index) {
  return landmark_nll(d, landmark_geometry(d, m.time_offset), m, index);
}

}  // namespace locbench::diagnosis
