#include "algorithms/diagnosis/diagnosis.h"

#include <tbb/parallel_invoke.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "algorithms/diagnosis/cause_catalog.h"
#include "algorithms/diagnosis/compass_channel.h"
#include "algorithms/diagnosis/landmark_channel.h"
#include "algorithms/diagnosis/odometry_channel.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::diagnosis {

// DiagnosisOptions' fields, stated once (diagnosis_types.h explains each).
template <class V>
void visit_fields(V& v, DiagnosisOptions& o) {
  v.field("false_alarm", o.false_alarm, "", open(0.0, 0.5), "per log and channel (Bonferroni over the causes)");
  v.field("window_s", o.windows.duration, "s", positive(), "window length");
  v.field("min_windows", o.windows.min_windows, "", non_negative(), "fewest windows to test");
  v.field("rpe_chain", o.rpe_chain, "", at_least(1), "windows chained into one relative-pose segment");
  v.field("holdout_block", o.block, "", at_least(1), "hold-out block length in windows");
}

void validate(const DiagnosisOptions& o) { validate_fields(o, "DiagnosisOptions"); }

LOCBENCH_OPTIONS_JSON(DiagnosisOptions)

namespace {

std::string verdict_of(const Diagnosis& d) {
  const std::string unconfirmed =
      d.unconfirmed.empty() ? ""
                            : fmt::format(
                                  " ({} cause(s) passed the likelihood-ratio test on the training windows but did "
                                  "not improve the held-out ones: see unconfirmed)",
                                  d.unconfirmed.size());
  if (d.detected.empty() && d.unexplained.empty()) {
    return fmt::format(
        "No significant discrepancy: the nominal model explains the residuals against {} "
        "at a false-alarm level of {} per channel{}.",
        d.reference, d.false_alarm, unconfirmed);
  }
  std::string s = "The nominal model ";
  if (!d.detected.empty()) {
    s += "misses ";
    for (std::size_t i = 0; i < d.detected.size(); ++i) {
      s += (i == 0 ? "" : i + 1 == d.detected.size() ? " and " : ", ") + d.detected[i];
    }
    if (!d.confounded.empty()) s += " (partly confounded: see confounded)";
  }
  if (!d.unexplained.empty()) {
    s += d.detected.empty() ? "leaves " : "; it also leaves ";
    s += fmt::format("{} residual structure(s) no catalog cause explains (first: {} of {} against {})",
                     d.unexplained.size(), d.unexplained[0].test, d.unexplained[0].residual,
                     d.unexplained[0].variable.empty() ? "nothing" : d.unexplained[0].variable);
  }
  return s + unconfirmed + ".";
}

// Why a residual structure that survived the kept causes is not accounted for: the catalog
// cause that would account for it, and what happened to it.
std::string reason_for(const ResidualTest& t, const std::vector<Cause>& causes,
                       const std::vector<std::pair<std::string, std::string>>& notes) {
  for (const auto& c : causes) {
    if (!accounts_for(cause_spec(c.id), t)) continue;
    for (const auto& [id, note] : notes) {
      if (id == c.id) return note;
    }
  }
  for (const auto& c : causes) {
    if (!accounts_for(cause_spec(c.id), t)) continue;
    if (c.detected) {
      return fmt::format("{} is kept and accounts for such structure; what remains is beyond its model", c.id);
    }
    if (c.statistic == "likelihood_ratio") {
      return fmt::format("{} would account for it, but its likelihood ratio {:.1f} stayed below {:.1f}", c.id, c.value,
                         c.threshold);
    }
  }
  return "no catalog cause accounts for it";
}

}  // namespace

Diagnosis diagnose_log(const Log& log, const DiagnosisOptions& options) {
  return diagnose_log(log, build_motion_data(log, options.windows), options);
}

Diagnosis diagnose_log(const Log& log, const MotionData& data, const DiagnosisOptions& options) {
  Diagnosis out;
  out.log = log.source.empty() ? log.name : log.source;
  out.false_alarm = options.false_alarm;
  out.reference = data.describe();
  if (data.odometry == OdometryKind::kEncoder) {
    out.nominal_model = {{"odometry", "encoder"},
                         {"meters_per_tick_left", data.nominal.meters_per_tick_left},
                         {"meters_per_tick_right", data.nominal.meters_per_tick_right},
                         {"wheelbase_m", data.nominal.wheelbase}};
  } else {
    out.nominal_model = {{"odometry", "logged pose / velocities"},
                         {"velocity_scale", 1.0},
                         {"turn_rate_scale", 1.0},
                         {"turn_rate_bias_rad_s", 0.0}};
  }
  out.nominal_model["noise"] = "constant white noise per window component (fitted)";

  // The channels are independent: they run side by side (each deterministic, so the report is
  // the same for any number of threads).
  const bool compass_testable = data.compass.size() >= 40 && data.truth.size() >= 2;
  const bool landmarks_testable = !log.landmarks.empty() && !log.landmark_map.empty() && log.truth.size() >= 2;
  OdometryChannelResult odometry;
  ChannelResult compass;
  LandmarkChannelResult landmarks;
  tbb::parallel_invoke([&] { odometry = diagnose_odometry(data, options); },
                       [&] {
                         if (compass_testable) compass = diagnose_compass(data, options);
                       },
                       [&] {
                         if (landmarks_testable) {
                           landmarks = diagnose_landmarks(
                               make_landmark_data(log.landmarks, log.landmark_map, log.truth), options);
                         }
                       });
  out.noise_window_s = options.windows.duration;
  out.noise_sigma_x = odometry.nominal_fit.sigma_x;
  out.noise_sigma_y = odometry.nominal_fit.sigma_y;
  out.noise_sigma_theta = odometry.nominal_fit.sigma_theta;
  // final_fit holds only the kept (held-out validated) causes: the odometry channel fits it on
  // the set left after backward elimination, which is exactly its detected causes.
  out.odometry_model = odometry.final_fit;
  out.odometry_kind = data.odometry == OdometryKind::kEncoder ? "encoder" : "velocity";
  std::vector<const ChannelResult*> channels{&odometry};
  if (compass_testable) {
    out.nominal_model["compass_resolution_rad"] = data.compass_step;
    out.reference += "; compass against TRUEPOS";
    channels.push_back(&compass);
  } else {
    out.not_testable.push_back("compass_bias, compass_quantization, compass_disturbance: need COMPASS and TRUEPOS");
  }
  if (landmarks.testable) {
    out.nominal_model["landmark"] = "z_r = ρ, z_b = φ (map positions, truth at the observation time), white noise";
    out.nominal_model["landmark_observations_used"] = landmarks.observations;
    out.nominal_model["landmark_observations_unmapped"] = landmarks.unmapped;
    out.reference += fmt::format("; {} landmark observations against TRUEPOS ({} of subjects not in the map left out)",
                                 landmarks.observations, landmarks.unmapped);
    out.landmark_model = landmarks.final_fit;
    channels.push_back(&landmarks);
  } else {
    out.not_testable.push_back(
        "landmark_range_scale, landmark_range_bias, landmark_range_off_axis_scale, landmark_bearing_bias, "
        "landmark_time_offset, "
        "landmark_range_dependent_noise, landmark_heavy_tails, landmark_position_error: need at least 40 landmark "
        "observations of mapped landmarks, a landmark map and TRUEPOS");
  }
  out.not_testable.push_back(
      "laser_range_bias, laser_range_scale: need laser scans and a map of the world, which a log does not carry");
  if (data.odometry == OdometryKind::kEncoder) {
    out.not_testable.push_back(
        "velocity_scale, speed_dependent_scale, turn_rate_scale, turn_rate_bias, drive_response: "
        "apply to velocity odometry (ODOM without ENCODER)");
  } else {
    out.not_testable.push_back(
        "wheel_diameter_ratio, wheelbase_scale, mean_diameter_scale, encoder_quantization, wheel_slip: need ENCODER "
        "counts");
  }
  if (data.reference == ReferenceKind::kCompass) {
    out.not_testable.push_back(
        "velocity_scale: a heading reference measures no distance (and E_o only through E_o/E_b)");
  }
  if (data.reference == ReferenceKind::kRelations) {
    out.not_testable.push_back(
        "sensor_time_offset: relations are stamped at the scans, which carry the odometry's clock");
  }

  // Judge once: every test of every channel at the level divided over all of them.
  std::vector<ResidualTest> remaining;
  std::vector<std::pair<std::string, std::string>> notes;
  for (const ChannelResult* c : channels) {
    out.residual_tests.insert(out.residual_tests.end(), c->tests.begin(), c->tests.end());
    remaining.insert(remaining.end(), c->remaining.begin(), c->remaining.end());
    out.causes.insert(out.causes.end(), c->causes.begin(), c->causes.end());
    out.confounded.insert(out.confounded.end(), c->confounded.begin(), c->confounded.end());
    out.overall_gain.insert(out.overall_gain.end(), c->overall_gain.begin(), c->overall_gain.end());
    notes.insert(notes.end(), c->heldout_notes.begin(), c->heldout_notes.end());
  }
  const double level = options.false_alarm / static_cast<double>(std::max<std::size_t>(out.residual_tests.size(), 1));
  for (auto* tests : {&out.residual_tests, &remaining}) {
    for (auto& t : *tests) t.passed = t.p_value > level;
  }
  for (const auto& t : remaining) {
    if (!t.passed)
      out.unexplained.push_back(
          {t.name, t.residual, t.variable, t.value, t.p_value, t.strength, reason_for(t, out.causes, notes)});
  }
  // Detected: odometry channel by evidence order, then compass; the causes that passed the
  // likelihood ratio but not the held-out check are listed apart (with their reason above).
  for (const auto& c : out.causes) {
    if (c.detected) out.detected.push_back(c.id);
    if (c.validated && !*c.validated) out.unconfirmed.push_back(c.id);
  }
  std::stable_sort(out.causes.begin(), out.causes.end(),
                   [](const Cause& a, const Cause& b) { return a.detected > b.detected; });
  out.verdict = verdict_of(out);
  return out;
}

}  // namespace locbench::diagnosis
