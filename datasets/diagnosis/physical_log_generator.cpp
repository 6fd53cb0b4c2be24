#include "datasets/diagnosis/physical_log_generator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/angle.h"
#include "core/errors.h"
#include "core/rng.h"

namespace locbench::sim {
namespace {

constexpr double kDt = 1e-3;  // integration step [s]

// Student-t with `dof` degrees of freedom scaled to unit variance (normal for dof = 0).
double unit_noise(Rng& rng, double dof) {
  if (!(dof > 0.0)) return rng.normal();
  double chi2 = 0.0;
  const int k = static_cast<int>(std::max(1.0, std::round(dof)));
  for (int i = 0; i < k; ++i) {
    const double z = rng.normal();
    chi2 += z * z;
  }
  const double t = rng.normal() / std::sqrt(chi2 / k);
  return k > 2 ? t * std::sqrt((k - 2.0) / k) : t;
}

Pose2 integrate(const Pose2& p, double v, double w, double dt) {
  const double th = p.theta + 0.5 * w * dt;
  return {p.x + v * dt * std::cos(th), p.y + v * dt * std::sin(th), wrap_angle(p.theta + w * dt)};
}

}  // namespace

Log generate_physical_log(const PhysicalEffects& e, std::uint64_t seed, const PhysicalOptions& o) {
  if (!(o.duration > 1.0) || !(o.odom_rate_hz > 0.0) || !(o.truth_rate_hz > 0.0) || !(o.compass_rate_hz > 0.0) ||
      !(e.velocity_scale > 0.0) || !(e.turn_rate_scale > 0.0) || e.drive_tau < 0.0 || e.heavy_tail_dof < 0.0 ||
      e.stall_rate < 0.0 || e.stall_duration < 0.0 || e.compass_step < 0.0 || e.compass_decimals < 0 ||
      e.compass_decimals > 12) {
    throw UsageError(
        "physical log generator: duration > 1 s, positive rates and scales, τ ≥ 0, dof ≥ 0, "
        "compass step ≥ 0 and 0–12 decimals expected");
  }
  Rng command_rng = Rng::stream(seed, 1), noise_rng = Rng::stream(seed, 2), sensor_rng = Rng::stream(seed, 3);
  Rng stall_rng = Rng::stream(seed, 4);
  double stall_until = -1.0;
  Log log;
  log.name = "sim/physical";
  log.source = fmt::format("physical generator (seed {})", seed);
  log.params["robot_wheelbase"] = "0.3";

  Pose2 truth, odom;
  double v_cmd = 0.0, w_cmd = 0.0, v_target = 0.0, w_target = 0.0, next_change = 0.0;
  double v_drive = 0.0, w_drive = 0.0;
  double block_v = 0.0, block_w = 0.0;  // process noise velocity over the current 100 ms block
  const long steps = static_cast<long>(std::round(o.duration / kDt));
  // Process noise is drawn per block: 100 ms for normal noise; 1 s for heavy tails, so that a
  // heavy-tailed draw is not averaged into a normal one before any window sees it.
  const long block = e.heavy_tail_dof > 0.0 ? 1000 : 100;
  const double block_s = static_cast<double>(block) * kDt;
  const double odom_period = 1.0 / o.odom_rate_hz, truth_period = 1.0 / o.truth_rate_hz;
  const double compass_period = 1.0 / o.compass_rate_hz;
  double next_odom = 0.0, next_truth = 0.0, next_compass = 0.0;
  const double print = std::pow(10.0, e.compass_decimals);
  for (long i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) * kDt;
    // Records at this instant (the state at true time t).
    if (t >= next_odom - 1e-12) {
      log.odometry.push_back({t + e.odometry_time_offset, odom, v_cmd, w_cmd});
      next_odom += odom_period;
    }
    if (t >= next_truth - 1e-12) {
      const Pose2 noisy(truth.x + sensor_rng.normal(0.0, o.truth_noise_xy),
                        truth.y + sensor_rng.normal(0.0, o.truth_noise_xy),
                        wrap_angle(truth.theta + sensor_rng.normal(0.0, o.truth_noise_theta)));
      log.truth.push_back({t, noisy, Pose2()});
      next_truth += truth_period;
    }
    if (o.compass && t >= next_compass - 1e-12) {
      double h = truth.theta + sensor_rng.normal(0.0, o.compass_noise);
      if (e.compass_step > 0.0) {
        h = e.compass_lattice_offset + e.compass_step * std::round((h - e.compass_lattice_offset) / e.compass_step);
      }
      h = wrap_angle(h);
      log.compass.push_back({t, std::round(h * print) / print});
      next_compass += compass_period;
    }
    if (i == steps) break;
    // The command: a new target every 1–4 s (a stop one time in six), slew-limited.
    if (t >= next_change) {
      v_target = command_rng.bernoulli(1.0 / 6.0) ? 0.0 : command_rng.uniform(0.05, 0.5);
      w_target = command_rng.uniform(-0.8, 0.8);
      next_change = t + command_rng.uniform(1.0, 4.0);
    }
    v_cmd += std::clamp(v_target - v_cmd, -2.0 * kDt, 2.0 * kDt);
    w_cmd += std::clamp(w_target - w_cmd, -4.0 * kDt, 4.0 * kDt);
    // The drive's first-order response, then the scales, then the process noise.
    if (e.drive_tau > 0.0) {
      const double a = 1.0 - std::exp(-kDt / e.drive_tau);
      v_drive += a * (v_cmd - v_drive);
      w_drive += a * (w_cmd - w_drive);
    } else {
      v_drive = v_cmd;
      w_drive = w_cmd;
    }
    if (i % block == 0) {
      block_v = o.process_noise_xy * std::sqrt(block_s) * unit_noise(noise_rng, e.heavy_tail_dof) / block_s;
      block_w = o.process_noise_theta * std::sqrt(block_s) * unit_noise(noise_rng, e.heavy_tail_dof) / block_s;
    }
    if (e.stall_rate > 0.0 && t >= stall_until && stall_rng.bernoulli(-std::expm1(-e.stall_rate * kDt))) {
      stall_until = t + e.stall_duration * stall_rng.uniform(0.5, 1.5);
    }
    const double moving = t < stall_until ? 0.0 : 1.0;
    const double v_true = moving * (e.velocity_scale + e.speed_slope * std::abs(v_cmd)) * v_drive + block_v;
    const double w_true = e.turn_rate_scale * w_drive + block_w;
    truth = integrate(truth, v_true, w_true, kDt);
    odom = integrate(odom, v_cmd, w_cmd, kDt);
  }
  std::sort(log.odometry.begin(), log.odometry.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
  return log;
}

}  // namespace locbench::sim
