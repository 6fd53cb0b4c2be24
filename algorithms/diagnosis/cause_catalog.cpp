#include "algorithms/diagnosis/cause_catalog.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "core/units.h"

namespace locbench::diagnosis {
namespace {

std::string ci(const Cause& c, std::size_t i) {
  if (c.parameters.size() <= i) return "?";
  const Estimate& e = c.parameters[i];
  return fmt::format("{:.6g} [{:.6g}, {:.6g}]", e.value, e.lo, e.hi);
}

bool encoder(const MotionData& d) { return d.odometry == OdometryKind::kEncoder; }
bool velocity(const MotionData& d) { return d.odometry == OdometryKind::kPose; }
bool velocity_with_distance(const MotionData& d) {
  return d.odometry == OdometryKind::kPose && d.reference != ReferenceKind::kCompass;
}
bool timed_reference(const MotionData& d) { return d.reference != ReferenceKind::kRelations; }

// Range-bearing observations of mapped landmarks against TRUEPOS (landmark_model.h).
void add_landmark_causes(std::vector<CauseSpec>& c) {
  const auto lk = PrimaryMetric::kLikelihood;
  c.push_back({.id = cause::kLandmarkRangeScale,
               .channel = "landmark",
               .params = {{"scale", "1", nullptr, 1.0, 1e-3, false, 0.8, 1.2}},
               .metric = lk,
               .explains = {"bias:landmark_range", "range_dependence:landmark_range"},
               .explain = [](const Cause& x) {
                 return "the measured ranges are " + ci(x, 0) + " times the true ones (z_r = scale·ρ + bias)";
               }});
  c.push_back({.id = cause::kLandmarkRangeBias,
               .channel = "landmark",
               .params = {{"bias_m", "m", nullptr, 0.0, 1e-3, false, -0.5, 0.5}},
               .metric = lk,
               .explains = {"bias:landmark_range"},
               .explain = [](const Cause& x) { return "the measured ranges carry a bias of " + ci(x, 0) + " m"; }});
  c.push_back({.id = cause::kLandmarkRangeOffAxis,
               .channel = "landmark",
               .params = {{"per_rad", "1/rad", nullptr, 0.0, 1e-3, false, -1.0, 1.0},
                          {"per_rad2", "1/rad²", nullptr, 0.0, 1e-3, false, -2.0, 2.0}},
               .metric = lk,
               .explains = {"off_axis_dependence:landmark_range"},
               .explain = [](const Cause& x) {
                 return "the range scale changes off the sensor's axis by " + ci(x, 0) + " per rad and " + ci(x, 1) +
                        " per rad² of bearing (z_r = (scale + k₁·φ + k₂·φ²)·ρ + bias): a camera reading range from "
                        "a landmark's apparent size, with lens distortion towards the image's edges";
               }});
  c.push_back({.id = cause::kLandmarkBearingBias,
               .channel = "landmark",
               .params = {{"bias_rad", "rad", nullptr, 0.0, 1e-3, false, -0.3, 0.3}},
               .metric = lk,
               .explains = {"bias:landmark_bearing"},
               .explain = [](const Cause& x) {
                 return "the measured bearings carry a bias of " + ci(x, 0) +
                        " rad (a camera mounted turned, or its optical axis off)";
               }});
  c.push_back({.id = cause::kLandmarkTimeOffset,
               .channel = "landmark",
               .params = {{"offset_s", "s", nullptr, 0.0, 0.01, false, -0.5, 0.5}},
               .metric = lk,
               .explains = {"lead_lag:landmark_bearing"},
               .explain = [](const Cause& x) {
                 return "the landmark observations are stamped " + ci(x, 0) +
                        " s after they were taken (logged − true): bearings lag the turns";
               }});
  c.push_back({.id = cause::kLandmarkRangeNoise,
               .channel = "landmark",
               .params = {{"slope", "m/m", nullptr, 0.01, 1e-3, true, 0.0, 0.5}},
               .metric = lk,
               .noise = true,
               .explains = {"heteroscedasticity:landmark_range", "heavy_tails:landmark_range"},
               .explain = [](const Cause& x) {
                 return "the range noise grows with range: σ_r(ρ)² = σ_r² + (" + ci(x, 0) +
                        "·ρ)², which the constant-noise model misses";
               }});
  c.push_back({.id = cause::kLandmarkTurnNoise,
               .channel = "landmark",
               .params = {{"slope", "s", nullptr, 0.01, 1e-3, true, 0.0, 0.5}},
               .metric = lk,
               .noise = true,
               .explains = {"heteroscedasticity:landmark_bearing", "heavy_tails:landmark_bearing"},
               .explain = [](const Cause& x) {
                 return "the bearing noise grows with the turn rate ω: σ_b(ω)² = σ_b² + (" + ci(x, 0) +
                        " s·ω)², which the constant-noise model misses (blur or timing jitter while turning)";
               }});
  c.push_back({.id = cause::kLandmarkPositionError,
               .channel = "landmark",
               .params = {{"dx_m", "m", nullptr, 0.0, 1e-2, false, -2.0, 2.0},
                          {"dy_m", "m", nullptr, 0.0, 1e-2, false, -2.0, 2.0}},
               .metric = lk,
               .explains = {"landmark_dependence:landmark_range", "landmark_dependence:landmark_bearing"},
               .explain = [](const Cause& x) {
                 const std::string id = x.extra.contains("landmark") ? x.extra["landmark"].dump() : "?";
                 return "landmark " + id + " is not where the map says: true − surveyed position (" + ci(x, 0) + ", " +
                        ci(x, 1) + ") m (the best of the landmarks searched)";
               }});
  c.push_back({.id = cause::kLandmarkHeavyTails,
               .channel = "landmark",
               .params = {{"dof", "1", nullptr, 5.0, 1.0, true, 0.5, 1e3}},
               .metric = lk,
               .noise = true,
               .generic = true,
               .explains = {"heavy_tails:landmark_range", "heavy_tails:landmark_bearing"},
               .explain = [](const Cause& x) {
                 return "the landmark residuals are heavy-tailed: Student-t with " + ci(x, 0) +
                        " degrees of freedom fits them better than the normal model (outliers: misread "
                        "barcodes, occlusions); all landmark fits use it";
               }});
}

// The wheels' geometry and slip, seen through encoder odometry.
void add_wheel_causes(std::vector<CauseSpec>& c) {
  using M = OdometryModel;
  c.push_back({.id = cause::kWheelDiameterRatio,
               .channel = "odometry",
               .params = {{"E_d", "1", &M::E_d, 1.0, 1e-3, false, 0.9, 1.1}},
               .metric = PrimaryMetric::kHeading,
               .explains = {"bias:heading", "drift_with_distance:heading"},
               .applies = encoder,
               .explain = [](const Cause& x) {
                 return "the wheels' diameters differ from the nominal ratio: E_d = D_R/D_L = " + ci(x, 0) +
                        " (eq. 2.1), so the odometry drifts in heading on straight lines";
               }});
  c.push_back({.id = cause::kWheelbaseScale,
               .channel = "odometry",
               .params = {{"E_b", "1", &M::E_b, 1.0, 1e-3, false, 0.8, 1.2}},
               .metric = PrimaryMetric::kHeading,
               .explains = {"drift_with_turning:heading"},
               .applies = encoder,
               .explain = [](const Cause& x) {
                 return "the effective wheelbase differs from the nominal one: E_b = " + ci(x, 0) +
                        " (eq. 2.2), so turns are over- or under-counted";
               }});
  // On heading-only references E_o and E_b act only through E_o/E_b (confounded, reported).
  c.push_back({.id = cause::kMeanDiameterScale,
               .channel = "odometry",
               .params = {{"E_o", "1", &M::E_o, 1.0, 1e-3, false, 0.8, 1.2}},
               .metric = PrimaryMetric::kTranslation,
               .explains = {"bias:along_track", "drift_with_distance:along_track", "drift_with_turning:heading"},
               .applies = encoder,
               .explain = [](const Cause& x) {
                 return "the mean wheel diameter differs from the nominal one: E_o = " + ci(x, 0) +
                        " (eq. 2.15), so every distance is scaled";
               }});
  c.push_back({.id = cause::kWheelSlip,
               .channel = "odometry",
               .params = {{"rate_per_m", "1/m", &M::slip_rate, 0.05, 0.01, true, 0.0, 10.0},
                          {"mean_loss", "1", &M::slip_loss, 0.2, 0.01, false, -1.0, 1.0}},
               .metric = PrimaryMetric::kLikelihood,
               .noise = true,
               .explains = {"heavy_tails:heading", "normality_skewness:heading", "heavy_tails:along_track"},
               .applies = encoder,
               .explain = [](const Cause& x) {
                 return "occasional wheel slip: " + ci(x, 0) + " events per metre of wheel travel, each losing " +
                        ci(x, 1) + " of one sample's travel of one wheel (§3.2) — heavy tails in the heading residual";
               }});
}

// The drive against logged velocities.
void add_velocity_causes(std::vector<CauseSpec>& c) {
  using M = OdometryModel;
  c.push_back({.id = cause::kVelocityScale,
               .channel = "odometry",
               .params = {{"scale", "1", &M::velocity_scale, 1.0, 1e-3, false, 0.5, 1.5}},
               .metric = PrimaryMetric::kTranslation,
               .explains = {"bias:along_track", "drift_with_distance:along_track", "speed_dependence:along_track"},
               .applies = velocity_with_distance,
               .explain = [](const Cause& x) {
                 return "the robot moves " + ci(x, 0) +
                        " times the logged distance (a velocity command the drive does not reach, or "
                        "a wheel radius off)";
               }});
  c.push_back({.id = cause::kSpeedDependentScale,
               .channel = "odometry",
               .params = {{"scale_at_0", "1", &M::velocity_scale, 1.0, 1e-3, false, 0.5, 1.5},
                          {"slope_s_per_m", "s/m", &M::speed_slope, 0.0, 1e-2, false, -2.0, 2.0}},
               .metric = PrimaryMetric::kTranslation,
               .explains = {"bias:along_track", "speed_dependence:along_track", "drift_with_distance:along_track"},
               .applies = velocity_with_distance,
               .explain = [](const Cause& x) {
                 return "the distance scale changes with speed: " + ci(x, 0) + " at rest, changing by " + ci(x, 1) +
                        " per m/s of logged speed";
               }});
  // A skewed along-track residual (windows that lose much of their distance, the rest at the
  // command) is not a scale: a symmetric noise model reads the slow windows as outliers and the
  // scale as the typical window's, while the path-length ratio is the mean's.
  c.push_back({.id = cause::kDriveStall,
               .channel = "odometry",
               .params = {{"rate_per_s", "1/s", &M::stall_rate, 0.1, 0.01, true, 0.0, 2.0},
                          {"duration_s", "s", &M::stall_duration, 0.4, 0.01, true, 0.0, 5.0}},
               .metric = PrimaryMetric::kTranslation,
               .explains = {"bias:along_track", "drift_with_distance:along_track", "speed_dependence:along_track"},
               .applies = velocity_with_distance,
               .explain = [](const Cause& x) {
                 std::string s = "the drive stalls now and then: " + ci(x, 0) +
                                 " episodes per second, each stopping the "
                                 "robot for " +
                                 ci(x, 1) + " s while the log keeps its velocity";
                 if (x.extra.contains("mean_distance_scale")) {
                   s += fmt::format(" — the robot covers {:.4g} of the logged distance on average",
                                    x.extra["mean_distance_scale"].get<double>());
                 }
                 return s;
               }});
  c.push_back({.id = cause::kTurnRateScale,
               .channel = "odometry",
               .params = {{"scale", "1", &M::turn_rate_scale, 1.0, 1e-3, false, 0.5, 1.5}},
               .metric = PrimaryMetric::kHeading,
               .explains = {"drift_with_turning:heading"},
               .applies = velocity,
               .explain = [](const Cause& x) { return "the robot turns " + ci(x, 0) + " times the logged turn"; }});
  c.push_back({.id = cause::kTurnRateBias,
               .channel = "odometry",
               .params = {{"bias_rad_s", "rad/s", &M::turn_rate_bias, 0.0, 1e-4, false, -0.5, 0.5}},
               .metric = PrimaryMetric::kHeading,
               .explains = {"bias:heading", "drift_with_distance:heading"},
               .applies = velocity,
               .explain = [](const Cause& x) { return "the logged turn rate has a bias of " + ci(x, 0) + " rad/s"; }});
  c.push_back({.id = cause::kDriveResponse,
               .channel = "odometry",
               .params = {{"tau_s", "s", &M::drive_tau, 0.1, 0.01, true, 0.0, 2.0}},
               .explains = {"lead_lag:heading", "autocorrelation:heading"},
               .applies = velocity,
               .explain = [](const Cause& x) {
                 return "the robot follows the logged velocity through a first-order drive response "
                        "with time constant τ = " +
                        ci(x, 0) + " s (a lag that smooths, unlike a pure time offset)";
               }});
}

// The noise, timing and resolution of any odometry.
void add_noise_and_timing_causes(std::vector<CauseSpec>& c) {
  using M = OdometryModel;
  c.push_back({.id = cause::kNoiseGrowth,
               .channel = "odometry",
               .params = {{"k2_m", "m", &M::k2, 1e-6, 1e-6, true, 0.0, 1.0}},
               .metric = PrimaryMetric::kLikelihood,
               .noise = true,
               .explains = {"heteroscedasticity:heading", "heteroscedasticity:along_track"},
               .explain = [](const Cause& x) {
                 return "odometry noise grows with travel: k² = " + ci(x, 0) +
                        " m² per metre of wheel travel (eq. 4.16), which the nominal constant-noise model misses";
               }});
  c.push_back({.id = cause::kHeavyTails,
               .channel = "odometry",
               .params = {{"dof", "1", &M::dof, 5.0, 1.0, true, 0.5, 1e3}},
               .metric = PrimaryMetric::kLikelihood,
               .noise = true,
               .generic = true,
               .explains = {"heavy_tails:heading", "heavy_tails:along_track", "normality_skewness:heading"},
               .explain = [](const Cause& x) {
                 return "the residuals are heavy-tailed: Student-t with " + ci(x, 0) +
                        " degrees of freedom fits them better than the normal model (occasional large "
                        "errors: collisions, slips, reference glitches); all fits use it";
               }});
  c.push_back({.id = cause::kTimeOffset,
               .channel = "odometry",
               .params = {{"offset_s", "s", &M::time_offset, 0.0, 0.01, false, -0.5, 0.5}},
               .explains = {"lead_lag:heading", "autocorrelation:heading"},
               .applies = timed_reference,
               .explain = [](const Cause& x) {
                 return "the " + x.extra.value("sensor", std::string("sensor")) +
                        " timestamps are offset from the reference by " + ci(x, 0) + " s (logged − true)";
               }});
  c.push_back({.id = cause::kEncoderQuantization,
               .channel = "odometry",
               .params = {{"step_m", "m"}},
               .metric = PrimaryMetric::kExact,
               .noise = true,
               .explains = {},
               .applies = encoder,
               .explain = [](const Cause& x) {
                 return "the encoders count in steps of " + ci(x, 0) + " m, coarser than the declared tick";
               }});
}

void add_compass_causes(std::vector<CauseSpec>& c) {
  // A lattice's round-off does not average out over a path with few headings: the moment tests
  // of the compass residual (mean, dependence on position) see it; the likelihood causes
  // (compass_bias, compass_disturbance) use the quantized density and judge those instead.
  c.push_back({.id = cause::kCompassQuantization,
               .channel = "compass",
               .params = {{"step_rad", "rad"}, {"offset_rad", "rad"}},
               .metric = PrimaryMetric::kExact,
               .noise = true,
               .explains = {"bias:compass", "position_dependence:compass", "heavy_tails:compass"},
               .explain = [](const Cause& x) {
                 return "the compass reports multiples of " + ci(x, 0) + " rad (" +
                        fmt::format("{:.4g}", to_deg(x.parameters.empty() ? 0.0 : x.parameters[0].value)) +
                        "°), coarser than declared";
               }});
  c.push_back({.id = cause::kCompassBias,
               .channel = "compass",
               .params = {{"bias_rad", "rad"}},
               .metric = PrimaryMetric::kLikelihood,
               .explains = {"bias:compass"},
               .explain = [](const Cause& x) { return "the compass has a constant bias of " + ci(x, 0) + " rad"; }});
  c.push_back({.id = cause::kCompassDisturbance,
               .channel = "compass",
               .params = {{"max_bias_rad", "rad"}},
               .metric = PrimaryMetric::kLikelihood,
               .explains = {"position_dependence:compass"},
               .explain = [](const Cause& x) {
                 return "the compass is disturbed in a region (see `region`): extra bias " + ci(x, 0) + " rad there";
               }});
}

std::vector<CauseSpec> build() {
  std::vector<CauseSpec> c;
  add_wheel_causes(c);
  add_velocity_causes(c);
  add_noise_and_timing_causes(c);
  add_compass_causes(c);
  add_landmark_causes(c);
  return c;
}

}  // namespace

const std::vector<CauseSpec>& cause_catalog() {
  static const std::vector<CauseSpec> catalog = build();
  return catalog;
}

const CauseSpec& cause_spec(std::string_view id) {
  for (const auto& c : cause_catalog()) {
    if (c.id == id) return c;
  }
  throw std::logic_error("cause catalog: unknown id '" + std::string(id) + "'");
}

std::vector<const CauseSpec*> odometry_causes(const MotionData& d) {
  std::vector<const CauseSpec*> out;
  for (const auto& c : cause_catalog()) {
    if (c.channel != "odometry" || c.metric == PrimaryMetric::kExact) continue;
    if (c.applies && !c.applies(d)) continue;
    out.push_back(&c);
  }
  return out;
}

std::vector<const CauseSpec*> landmark_causes() {
  std::vector<const CauseSpec*> out;
  for (const auto& c : cause_catalog()) {
    if (c.channel == "landmark") out.push_back(&c);
  }
  return out;
}

std::string explain(const Cause& c) {
  const CauseSpec& s = cause_spec(c.id);
  return s.explain ? s.explain(c) : std::string();
}

bool accounts_for(const CauseSpec& spec, const ResidualTest& t) {
  const std::string key = t.name + ":" + t.residual;
  return std::find(spec.explains.begin(), spec.explains.end(), key) != spec.explains.end();
}

std::string to_string(PrimaryMetric m) {
  switch (m) {
    case PrimaryMetric::kTranslation: return "heldout_translation_error_m";
    case PrimaryMetric::kHeading: return "heldout_heading_error_rad";
    case PrimaryMetric::kTranslationOrHeading: return "heldout_translation_or_heading_error";
    case PrimaryMetric::kLikelihood: return "heldout_nll_per_window";
    case PrimaryMetric::kExact: return "exact";
  }
  return "?";
}

}  // namespace locbench::diagnosis
