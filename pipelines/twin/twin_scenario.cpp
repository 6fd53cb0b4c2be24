#include "pipelines/twin/twin_scenario.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>

#include "core/angle.h"
#include "core/errors.h"
#include "core/statistics.h"
#include "datasets/io/odometry_interpolation.h"
#include "datasets/sim/simulator.h"
#include "pipelines/twin/replay_commands.h"
#include "pipelines/twin/twin_residuals.h"

namespace locbench::sim {
using io::interpolate_odometry, io::interpolate_truth;
namespace {

std::string log_label(const Log& log) { return log.source.empty() ? log.name : log.source; }

// The kept causes' parameters, "id.parameter" → value.
std::map<std::string, double> kept_parameters(const diagnosis::Diagnosis& d) {
  std::map<std::string, double> p;
  for (const auto& c : d.causes) {
    if (!c.detected) continue;
    for (const auto& e : c.parameters) p[c.id + "." + e.name] = e.value;
  }
  return p;
}

// A positive finite PARAM value; InputError naming the PARAM otherwise.
double param_number(const Log& log, const std::string& name) {
  const std::string& text = log.params.at(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0.0)) {
    throw InputError(log_label(log), 0, "PARAM " + name + " = '" + text + "': expected a positive number");
  }
  return v;
}

double median_interval(const std::vector<double>& t) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i] > t[i - 1]) dt.push_back(t[i] - t[i - 1]);
  }
  return dt.empty() ? 0.0 : quantile(dt, 0.5);
}

double robust_sigma(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const double med = quantile(v, 0.5);
  for (double& x : v) x = std::abs(x - med);
  return 1.4826 * quantile(v, 0.5);
}

}  // namespace

std::vector<CauseMapping> apply_causes(const diagnosis::Diagnosis& d, Scenario& s) {
  std::vector<CauseMapping> out;
  std::map<std::string, double> p = kept_parameters(d);
  DriveResponse& r = s.drive.response;
  double speed_scale = 1.0;
  for (const auto& c : d.causes) {
    if (!c.detected) continue;
    CauseMapping m{c.id, true, ""};
    const auto need = [&](const std::string& name) -> std::optional<double> {
      const auto it = p.find(c.id + "." + name);
      if (it == p.end()) {
        m.simulated = false;
        m.how = "not simulated: parameter '" + name + "' missing from the diagnosis";
        return std::nullopt;
      }
      return it->second;
    };
    if (c.id == "velocity_scale") {
      if (const auto v = need("scale")) {
        speed_scale *= *v;
        m.how = fmt::format("drive.response.velocity_scale ×= {:.6g}", *v);
      }
    } else if (c.id == "speed_dependent_scale") {
      const auto s0 = need("scale_at_0");
      const auto slope = need("slope_s_per_m");
      if (s0 && slope) {
        r.velocity_scale = *s0;
        r.speed_slope = *slope;
        m.how = fmt::format("drive.response.velocity_scale = {:.6g}, speed_slope = {:.6g} s/m", *s0, *slope);
      }
    } else if (c.id == "drive_stall") {
      const auto rate = need("rate_per_s");
      const auto duration = need("duration_s");
      if (rate && duration) {
        r.stall_rate = std::max(*rate, 0.0);
        r.stall_duration = std::max(*duration, 0.0);
        m.how = fmt::format("drive.response.stall_rate = {:.6g} /s, stall_duration = {:.6g} s", r.stall_rate,
                            r.stall_duration);
      }
    } else if (c.id == "turn_rate_scale") {
      if (const auto v = need("scale")) {
        r.turn_rate_scale = *v;
        m.how = fmt::format("drive.response.turn_rate_scale = {:.6g}", *v);
      }
    } else if (c.id == "turn_rate_bias") {
      if (const auto v = need("bias_rad_s")) {
        r.turn_rate_bias = *v;
        m.how = fmt::format("drive.response.turn_rate_bias = {:.6g} rad/s", *v);
      }
    } else if (c.id == "drive_response") {
      if (const auto v = need("tau_s")) {
        r.time_constant = std::max(*v, 0.0);
        m.how = fmt::format("drive.response.time_constant = {:.6g} s", r.time_constant);
      }
    } else if (c.id == "sensor_time_offset") {
      const std::string sensor = c.extra.value("sensor", std::string("odometry"));
      if (sensor != "odometry") {
        m.simulated = false;
        m.how = "not simulated: the offset is the compass's (" + sensor + "); the twin has no compass";
      } else if (const auto v = need("offset_s")) {
        (s.odometry.timing.enabled ? s.odometry.timing : s.encoders.timing).latency = *v;
        m.how = fmt::format("{}.latency = {:.6g} s", s.odometry.timing.enabled ? "odometry" : "encoders", *v);
      }
    } else if (c.id == "wheel_diameter_ratio" || c.id == "wheelbase_scale" || c.id == "mean_diameter_scale") {
      const char* name = c.id == "wheel_diameter_ratio" ? "E_d" : c.id == "wheelbase_scale" ? "E_b" : "E_o";
      if (const auto v = need(name)) m.how = fmt::format("robot.actual from {} = {:.6g}", name, *v);
    } else if (c.id == "odometry_noise_growth") {
      if (const auto v = need("k2_m")) {
        s.floor.k_left = s.floor.k_right = std::sqrt(std::max(*v, 0.0));
        m.how = fmt::format("floor.k_left = floor.k_right = √{:.6g} = {:.6g} √m", *v, s.floor.k_left);
      }
    } else if (c.id == "wheel_slip") {
      const auto rate = need("rate_per_m");
      const auto loss = need("mean_loss");
      if (rate && loss) {
        s.slip.unit = SlipRateUnit::kPerMetre;
        const double l = std::clamp(*loss, 0.0, 0.75);
        s.slip.straight = s.slip.turn = SlipProfile{std::max(*rate, 0.0), 2.0 * l / 3.0, 4.0 * l / 3.0};
        m.how = fmt::format("slip per metre, rate {:.6g}, loss U[{:.3g}, {:.3g}]", *rate, 2.0 * l / 3.0, 4.0 * l / 3.0);
      }
    } else if (c.id == "heavy_tailed_noise") {
      if (const auto v = need("dof")) {
        s.motion_noise.dof = std::max(*v, 0.0);
        m.how = fmt::format("motion_noise.dof = {:.6g} (Student-t windows)", *v);
      }
    } else if (c.id == "encoder_quantization") {
      m.how = "reproduced by the replay: the twin's encoder counts are the logged ones";
    } else {
      m.simulated = false;
      m.how = c.channel == "compass" ? "not simulated: the twin replays odometry against a position reference and has "
                                       "no compass channel"
                                     : "not simulated: no simulator mapping for this cause";
    }
    out.push_back(m);
  }
  r.velocity_scale *= speed_scale;
  r.speed_slope *= speed_scale;
  const double ed = p.count("wheel_diameter_ratio.E_d") ? p["wheel_diameter_ratio.E_d"] : 1.0;
  const double eb = p.count("wheelbase_scale.E_b") ? p["wheelbase_scale.E_b"] : 1.0;
  const double eo = p.count("mean_diameter_scale.E_o") ? p["mean_diameter_scale.E_o"] : 1.0;
  s.robot.actual.diameter_left = s.robot.nominal.diameter_left * eo * 2.0 / (1.0 + ed);
  s.robot.actual.diameter_right = s.robot.nominal.diameter_right * eo * 2.0 * ed / (1.0 + ed);
  s.robot.actual.wheelbase = s.robot.nominal.wheelbase * eb;
  return out;
}

std::pair<double, double> reference_noise(const std::vector<TruePose>& truth) {
  std::vector<double> dx, dy, dth;
  for (std::size_t k = 1; k + 1 < truth.size(); ++k) {
    const double h1 = truth[k].t - truth[k - 1].t, h2 = truth[k + 1].t - truth[k].t;
    if (!(h1 > 0.0 && h2 > 0.0) || std::abs(h1 - h2) > 0.1 * std::max(h1, h2)) continue;
    const Pose2 &a = truth[k - 1].pose, &b = truth[k].pose, &c = truth[k + 1].pose;
    dx.push_back(c.x - 2.0 * b.x + a.x);
    dy.push_back(c.y - 2.0 * b.y + a.y);
    dth.push_back(angle_diff(c.theta, b.theta) - angle_diff(b.theta, a.theta));
  }
  if (dx.size() < 20) return {0.0, 0.0};
  const double xy = std::sqrt(0.5 * (std::pow(robust_sigma(dx), 2) + std::pow(robust_sigma(dy), 2)));
  return {xy / std::sqrt(6.0), robust_sigma(dth) / std::sqrt(6.0)};
}

Log twin_log(const Scenario& twin, std::uint64_t seed, const Log& real) {
  Log log = simulate(twin, seed).log;
  log.name = "twin/" + real.name;
  log.source = "simulated twin of " + log_label(real);
  return log;
}

namespace {

// Moment-matched floor (σ_x, σ_y, σ_θ per window) of a twin scenario against the log's windows.
std::array<double, 3> fit_floor(const Scenario& s, const diagnosis::MotionData& windows, const Log& real_log,
                                double origin, std::uint64_t seed) {
  Scenario det = s;
  det.motion_noise.sigma_along = det.motion_noise.sigma_left = det.motion_noise.sigma_heading = 0.0;
  Scenario noisy = det;
  det.truth.noise_xy = det.truth.noise_theta = 0.0;
  det.floor.k_left = det.floor.k_right = 0.0;
  det.slip.straight.rate = det.slip.turn.rate = 0.0;
  const auto real = nominal_residuals(windows);
  const auto rd = twin_residuals(windows, twin_log(det, seed, real_log), origin);
  const auto rn = twin_residuals(windows, twin_log(noisy, seed, real_log), origin);
  std::array<double, 3> sigma{};
  const double dof = s.motion_noise.dof;
  for (int c = 0; c < 3; ++c) {
    const auto v = common_component({&real, &rd, &rn}, c);
    const std::size_t n = v[0].size();
    if (n < 5) {
      throw InputError(
          log_label(real_log), 0,
          fmt::format("only {} windows of the twin line up with the log's reference; cannot fit its noise floor", n));
    }
    std::vector<double> real_noise(n), other_noise(n);  // the log's and the other sources'
    for (std::size_t k = 0; k < n; ++k) {
      real_noise[k] = v[0][k] - v[1][k];
      other_noise[k] = v[2][k] - v[1][k];
    }
    double floor = 0.0;
    if (dof > 0.0) {
      // Student-t windows: their variance is infinite for dof ≤ 2 and, above, decided by a few
      // windows, so the spread is matched robustly — the 1.4826·MAD scale of the log's noise
      // less the other sources' (in quadrature), turned into the t scale with the same MAD.
      const double spread =
          std::sqrt(std::max(std::pow(robust_sigma(real_noise), 2) - std::pow(robust_sigma(other_noise), 2), 0.0));
      floor = spread * normal_quantile(0.75) / student_t_critical(0.5, dof);  // t_{0.75, dof}
    } else {
      double real_ms = 0.0, noise_ms = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        real_ms += real_noise[k] * real_noise[k];
        noise_ms += other_noise[k] * other_noise[k];
      }
      floor = std::sqrt(std::max(real_ms - noise_ms, 0.0) / static_cast<double>(n));
    }
    sigma[static_cast<std::size_t>(c)] = floor;
  }
  return sigma;
}

void set_floor(Scenario& s, const std::array<double, 3>& sigma) {
  s.motion_noise.sigma_along = sigma[0];
  s.motion_noise.sigma_left = sigma[1];
  s.motion_noise.sigma_heading = sigma[2];
}

}  // namespace

Twin build_twin(const Log& log, const diagnosis::Diagnosis& d, const TwinOptions& options) {
  if (log.truth.empty() && log.relations.empty()) {
    throw InputError(log_label(log), 0,
                     "a twin needs a position reference (TRUEPOS or relations) to fit its noise floor against");
  }
  const ReplaySource src = replay_commands(log, options.from, options.to);
  Twin twin;
  twin.diagnosis_floor[0] = d.noise_sigma_x;
  twin.diagnosis_floor[1] = d.noise_sigma_y;
  twin.diagnosis_floor[2] = d.noise_sigma_theta;

  Scenario base;
  base.name = "twin/" + log.name;
  base.world.kind = WorldKind::kNone;
  base.motion.kind = MotionKind::kReplay;
  base.physics.trajectory_rate = 10.0;
  base.drive.pause = 0.0;
  if (const auto m = log.nominal_model()) {
    const double cpr =
        log.params.count("robot_encoder_counts_per_rev") ? param_number(log, "robot_encoder_counts_per_rev") : 2000.0;
    base.robot.encoder = {1.0, cpr};
    base.robot.nominal = {m->meters_per_tick_left * cpr / kPi, m->meters_per_tick_right * cpr / kPi, m->wheelbase};
  } else {
    // Velocity odometry without a declared model: the diagnosis's default wheelbase, 0.1 mm ticks.
    const auto it = log.params.find(kParamWheelbase);
    base.robot.nominal.wheelbase = it != log.params.end() ? param_number(log, kParamWheelbase) : 0.5;
  }
  base.robot.actual = base.robot.nominal;
  std::vector<double> times;
  for (const auto& c : src.commands) times.push_back(c.t);
  const double rate = 1.0 / std::max(median_interval(times), 1e-3);
  base.encoders.timing = SensorTiming{src.odometry == "ENCODER", rate, 0.0, 0.0};
  base.odometry.timing = SensorTiming{src.odometry == "ODOM", rate, 0.0, 0.0};
  if (!log.truth.empty()) {
    std::vector<double> tt;
    for (const auto& t : log.truth) tt.push_back(t.t);
    base.truth.rate = std::min(1.0 / std::max(median_interval(tt), 1e-3), 1000.0);
    const auto [xy, th] = reference_noise(log.truth);
    base.truth.noise_xy = xy;
    base.truth.noise_theta = th;
  } else {
    base.truth.rate = 100.0;  // the relations windows are read from it (twin_residuals.h)
  }
  base.motion_noise.window = d.noise_window_s;

  Scenario extended = base;
  twin.causes = apply_causes(d, extended);
  for (const auto& m : twin.causes) {
    if (!m.simulated) twin.not_simulated.push_back(m.id);
  }
  // Time: the twin starts standing for 1 s (plus any positive latency) before the first command.
  const double latency = std::max({extended.odometry.timing.latency, extended.encoders.timing.latency, 0.0});
  twin.time_origin = src.commands.front().t - 1.0 - latency;
  std::vector<ReplayCommand> commands = src.commands;
  for (auto& c : commands) c.t -= twin.time_origin;
  base.motion.commands = extended.motion.commands = commands;
  const double t_first = src.commands.front().t;
  std::optional<Pose2> start = log.truth.empty() ? interpolate_odometry(log, t_first) : interpolate_truth(log, t_first);
  if (!start && !log.truth.empty()) start = log.truth.front().pose;
  base.start = extended.start = start.value_or(Pose2{});

  twin.residual_window_s = d.noise_window_s;
  twin.residual_windows = residual_windows(log, d.noise_window_s);
  const diagnosis::MotionData& windows = twin.residual_windows;
  set_floor(base, fit_floor(base, windows, log, twin.time_origin, options.calibration_seed));
  set_floor(extended, fit_floor(extended, windows, log, twin.time_origin, options.calibration_seed));

  const auto describe = [&](Scenario& s, const char* model) {
    s.name = fmt::format("twin/{}/{}", log.name, model);
    s.description = fmt::format(
        "Synthetic twin of {} under the {} model: its {} replayed ({} commands, logged time = twin time + {:.6f} s), "
        "reference as the log's ({}).",
        log_label(log), model, src.odometry, commands.size(), twin.time_origin, d.reference);
    s.notes.push_back(
        fmt::format("noise floor per {:g} s window (moment-matched on windows paired with the log): σ_x = {:.4g} m, "
                    "σ_y = {:.4g} m, "
                    "σ_θ = {:.4g} rad; the diagnosis's nominal floor: {:.4g} m, {:.4g} m, {:.4g} rad",
                    s.motion_noise.window, s.motion_noise.sigma_along, s.motion_noise.sigma_left,
                    s.motion_noise.sigma_heading, d.noise_sigma_x, d.noise_sigma_y, d.noise_sigma_theta));
  };
  describe(base, "nominal");
  describe(extended, "extended");
  for (const auto& m : twin.causes) extended.notes.push_back(m.id + ": " + m.how);
  if (twin.causes.empty())
    extended.notes.push_back("the diagnosis kept no cause: the extended twin is the nominal one");
  for (const auto& id : twin.not_simulated) {
    base.notes.push_back("kept cause not simulated by the extended twin: " + id);
  }
  twin.nominal = std::move(base);
  twin.extended = std::move(extended);
  return twin;
}

}  // namespace locbench::sim
