#include "datasets/diagnosis/hidden_effects.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/angle.h"
#include "core/errors.h"
#include "core/rng.h"
#include "core/units.h"
#include "datasets/sim/simulator.h"

namespace locbench::sim {

std::vector<std::pair<std::string, std::string>> hidden_effect_ids() {
  return {{"wheel_diameter_ratio", "E_d − 1"},
          {"wheelbase_scale", "E_b − 1"},
          {"mean_diameter_scale", "E_o − 1"},
          {"encoder_quantization", "step in ticks (integer ≥ 2)"},
          {"compass_quantization", "step [rad]"},
          {"compass_bias", "bias [rad]"},
          {"compass_disturbance", "extra bias in a 1.5 m disc [rad]"},
          {"wheel_slip", "events per metre of wheel travel (loss U[0.2, 0.4])"},
          {"odometry_noise_growth", "k² [m per m of wheel travel]"},
          {"velocity_scale", "scale − 1 (true = scale × logged; velocity odometry)"},
          {"turn_rate_scale", "scale − 1 (velocity odometry)"},
          {"turn_rate_bias", "bias [rad/s] (velocity odometry)"},
          {"sensor_time_offset", "odometry latency [s] (logged − true)"}};
}

namespace {

bool known(const std::string& id) {
  for (const auto& [k, u] : hidden_effect_ids()) {
    if (k == id) return true;
  }
  return false;
}

// ΔD, Δθ of consecutive ODOM poses, rescaled and re-integrated.
void distort_velocity_odometry(Log& log, double vscale, double wscale, double wbias) {
  if (log.odometry.size() < 2) return;
  std::vector<OdometryReading> out{log.odometry.front()};
  Pose2 p = log.odometry.front().pose;
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    const auto& a = log.odometry[i - 1];
    const auto& b = log.odometry[i];
    const double dt = b.t - a.t;
    const double dth = angle_diff(b.pose.theta, a.pose.theta);
    const double mid = a.pose.theta + 0.5 * dth;
    const double dx = b.pose.x - a.pose.x, dy = b.pose.y - a.pose.y;
    double d = std::hypot(dx, dy);
    if (dx * std::cos(mid) + dy * std::sin(mid) < 0.0) d = -d;
    const double ld = d / vscale, lth = (dth - wbias * dt) / wscale;
    const double half = 0.5 * lth;
    const double chord = std::abs(half) < 1e-6 ? ld : ld * std::sin(half) / half;
    p = Pose2(p.x + chord * std::cos(p.theta + half), p.y + chord * std::sin(p.theta + half), p.theta + lth);
    OdometryReading r = b;
    r.pose = p;
    r.tv = dt > 0 ? ld / dt : 0.0;
    r.rv = dt > 0 ? lth / dt : 0.0;
    out.push_back(r);
  }
  log.odometry = out;
}

// The random path the effects are hidden in: waypoints in the square of side `area` (drawn from
// `rng`), encoders, truth at every physics step, velocity odometry and compass as asked.
Scenario random_path_scenario(const GeneratorOptions& o, Rng& rng) {
  Scenario s;
  s.name = "hidden_effects";
  s.world.kind = WorldKind::kNone;
  s.motion.kind = MotionKind::kWaypoints;
  s.start = Pose2(0.5 * o.area, 0.5 * o.area, rng.uniform(-kPi, kPi));
  for (int i = 0; i < o.waypoints; ++i) {
    s.motion.waypoints.emplace_back(rng.uniform(0.0, o.area), rng.uniform(0.0, o.area));
  }
  s.drive.speed = 0.3;
  s.drive.turn_rate = deg(45.0);
  s.drive.pause = 0.3;
  s.encoders.timing = SensorTiming{true, 10.0, 0.0, 0.005};  // jitter: increments vary
  // TRUEPOS at every physics step: linear interpolation would cut the corners of the
  // instantaneous leg starts (heavy-tailed residuals and a spurious ~0.7 ms offset at 100 Hz).
  s.truth.rate = 1000.0;
  if (o.velocity_odometry) s.odometry.timing = SensorTiming{true, 10.0, 0.0, 0.005};
  if (o.compass) {
    s.compass.timing = SensorTiming{true, 10.0, 0.0, 0.005};  // between the truth samples, as on a real robot
    s.compass.noise = deg(0.2);
  }
  return s;
}

// What the effects do to the log after the simulation.
struct LogDistortion {
  double vscale = 1.0, wscale = 1.0, wbias = 0.0;  // velocity odometry
  std::int64_t tick_step = 1;                      // encoder quantization
};

// Each effect put into the scenario (or into the distortion of the log), with the true value of
// its parameters in `truth`; a disturbance's disc is centred on a waypoint drawn from `rng`.
LogDistortion hide_effects(const std::vector<HiddenEffect>& effects, const GeneratorOptions& o, Rng& rng, Scenario& s,
                           std::map<std::string, double>& truth) {
  LogDistortion out;
  const double dn = s.robot.nominal.mean_diameter();
  for (const auto& e : effects) {
    if (!known(e.id)) throw UsageError("hidden effect: unknown id '" + e.id + "'");
    if (!std::isfinite(e.magnitude)) throw UsageError("hidden effect " + e.id + ": magnitude must be finite");
    const double m = e.magnitude;
    if (e.id == "wheel_diameter_ratio") {
      const double ed = 1.0 + m;
      const double mean = s.robot.actual.mean_diameter();
      s.robot.actual.diameter_left = mean * 2.0 / (1.0 + ed);
      s.robot.actual.diameter_right = mean * 2.0 * ed / (1.0 + ed);
      truth["wheel_diameter_ratio.E_d"] = ed;
    } else if (e.id == "wheelbase_scale") {
      s.robot.actual.wheelbase = s.robot.nominal.wheelbase * (1.0 + m);
      truth["wheelbase_scale.E_b"] = 1.0 + m;
    } else if (e.id == "mean_diameter_scale") {
      s.robot.actual.diameter_left *= 1.0 + m;
      s.robot.actual.diameter_right *= 1.0 + m;
      truth["mean_diameter_scale.E_o"] = 1.0 + m;
    } else if (e.id == "encoder_quantization") {
      out.tick_step = static_cast<std::int64_t>(std::llround(m));
      if (out.tick_step < 2) throw UsageError("encoder_quantization: the step must be an integer ≥ 2 ticks");
      truth["encoder_quantization.step_m"] =
          static_cast<double>(out.tick_step) * kPi * dn / s.robot.encoder.counts_per_wheel_rev();
    } else if (e.id == "compass_quantization") {
      s.compass.resolution = 2.0 * kPi / std::round(2.0 * kPi / m);  // a divisor of 2π
      truth["compass_quantization.step_rad"] = s.compass.resolution;
    } else if (e.id == "compass_bias") {
      s.compass.bias = m;
      truth["compass_bias.bias_rad"] = m;
    } else if (e.id == "compass_disturbance") {
      DisturbanceZone z;
      z.shape = DisturbanceZone::Shape::kCircle;
      z.center =
          s.motion.waypoints[static_cast<std::size_t>(rng.uniform(0.0, 0.999) * static_cast<double>(o.waypoints))];
      z.radius = 1.5;
      z.bias = m;
      s.compass.zones.push_back(z);
      truth["compass_disturbance.max_bias_rad"] = m;
      truth["compass_disturbance.center_x"] = z.center.x();
      truth["compass_disturbance.center_y"] = z.center.y();
    } else if (e.id == "wheel_slip") {
      s.slip.unit = SlipRateUnit::kPerMetre;
      s.slip.straight = {m, 0.2, 0.4};
      s.slip.turn = {m, 0.2, 0.4};
      truth["wheel_slip.rate_per_m"] = m;
      truth["wheel_slip.mean_loss"] = 0.3;
    } else if (e.id == "odometry_noise_growth") {
      if (m < 0.0) throw UsageError("odometry_noise_growth: k² must be ≥ 0");
      s.floor.k_left = s.floor.k_right = std::sqrt(m);
      truth["odometry_noise_growth.k2_m"] = m;
    } else if (e.id == "velocity_scale") {
      out.vscale = 1.0 + m;
      truth["velocity_scale.scale"] = out.vscale;
    } else if (e.id == "turn_rate_scale") {
      out.wscale = 1.0 + m;
      truth["turn_rate_scale.scale"] = out.wscale;
    } else if (e.id == "turn_rate_bias") {
      out.wbias = m;
      truth["turn_rate_bias.bias_rad_s"] = m;
    } else if (e.id == "sensor_time_offset") {
      if (o.velocity_odometry)
        s.odometry.timing.latency = m;
      else
        s.encoders.timing.latency = m;
      truth["sensor_time_offset.offset_s"] = m;
    }
  }
  return out;
}

// Encoder counts rounded down to multiples of `step` ticks.
void quantize_encoders(std::vector<EncoderReading>& encoders, std::int64_t step) {
  for (auto& e : encoders) {
    auto q = [&](std::int64_t n) { return (n >= 0 ? n / step : -((-n + step - 1) / step)) * step; };
    e.left = q(e.left);
    e.right = q(e.right);
  }
}

// Relations between odometry instants about 1 s apart, from the (noisy) truth.
std::vector<Relation> relations_from_truth(const Log& log) {
  std::vector<Relation> relations;
  std::vector<double> times;
  for (const auto& e : log.encoders) times.push_back(e.t);
  for (const auto& e : log.odometry) times.push_back(e.t);
  std::optional<double> t1;
  auto pose_at = [&](double t) -> std::optional<Pose2> {
    auto it =
        std::lower_bound(log.truth.begin(), log.truth.end(), t, [](const TruePose& p, double v) { return p.t < v; });
    if (it == log.truth.begin() || it == log.truth.end()) return std::nullopt;
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double f = (t - a.t) / (b.t - a.t);
    return Pose2(a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
                 a.pose.theta + f * angle_diff(b.pose.theta, a.pose.theta));
  };
  for (double t : times) {
    if (!t1) {
      t1 = t;
      continue;
    }
    if (t - *t1 < 1.0) continue;
    const auto a = pose_at(*t1), b = pose_at(t);
    if (a && b) relations.push_back({*t1, t, between(*a, *b)});
    t1 = t;
  }
  return relations;
}

}  // namespace

GeneratedLog generate_log(const std::vector<HiddenEffect>& effects, std::uint64_t seed, const GeneratorOptions& o) {
  Rng rng = Rng::stream(seed, 0);
  Scenario s = random_path_scenario(o, rng);
  GeneratedLog g;
  g.effects = effects;
  const LogDistortion distortion = hide_effects(effects, o, rng, s, g.truth);
  g.log = simulate(s, Rng::derive_seed(seed, 1)).log;
  Log& log = g.log;
  log.name = "sim/hidden_effects";
  log.source = fmt::format("generated(seed={})", seed);
  // The PARAM records declare the nominal model only: nothing of the hidden effects.
  for (auto it = log.params.begin(); it != log.params.end();) {
    it = it->first.rfind("sim_", 0) == 0 ? log.params.erase(it) : std::next(it);
  }
  if (o.compass) log.params["compass_resolution"] = "0";
  if (distortion.tick_step > 1) quantize_encoders(log.encoders, distortion.tick_step);
  if (o.velocity_odometry) {
    log.encoders.clear();
    distort_velocity_odometry(log, distortion.vscale, distortion.wscale, distortion.wbias);
  } else {
    log.odometry.clear();
  }
  Rng noise = Rng::stream(seed, 2);
  for (auto& t : log.truth) {
    t.pose =
        Pose2(t.pose.x + noise.normal(0.0, o.reference_noise_xy), t.pose.y + noise.normal(0.0, o.reference_noise_xy),
              t.pose.theta + noise.normal(0.0, o.reference_noise_theta));
  }
  log.laser.clear();
  if (o.reference == GeneratedReference::kRelations) {
    log.relations = relations_from_truth(log);
    log.truth.clear();
  } else if (o.reference == GeneratedReference::kCompass) {
    log.truth.clear();
  }
  return g;
}

}  // namespace locbench::sim
