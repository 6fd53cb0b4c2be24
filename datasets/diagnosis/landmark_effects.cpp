#include "datasets/diagnosis/landmark_effects.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/angle.h"
#include "core/errors.h"
#include "core/rng.h"

namespace locbench::sim {

std::vector<std::pair<std::string, std::string>> landmark_effect_ids() {
  return {
      {"landmark_range_scale", "scale − 1 (measured = scale × true range)"},
      {"landmark_range_bias", "bias [m]"},
      {"landmark_range_off_axis_scale", "k₂: measured = (1 + 0.1·k₂·φ + k₂·φ²) × true range, φ the bearing [1/rad²]"},
      {"landmark_bearing_bias", "bias [rad]"},
      {"landmark_time_offset", "observation latency [s] (logged − true)"},
      {"landmark_range_dependent_noise", "slope: σ_r(ρ)² = σ_r² + (slope·ρ)² [m/m]"},
      {"landmark_turn_dependent_bearing_noise", "slope: σ_b(ω)² = σ_b² + (slope·ω)² [s]"},
      {"landmark_heavy_tails", "Student-t degrees of freedom of both noises (integer ≥ 1)"},
      {"landmark_position_error", "one landmark's true − surveyed distance [m] (random direction)"}};
}

namespace {

struct Camera {
  double range_scale = 1.0, range_bias = 0.0, off_axis = 0.0, bearing_bias = 0.0, offset = 0.0, slope = 0.0,
         turn_slope = 0.0;
  int dof = 0;
  int displaced = -1;  // map index
  double dx = 0.0, dy = 0.0;
};

Camera camera_of(const std::vector<HiddenEffect>& effects, int landmarks, Rng& rng,
                 std::map<std::string, double>& truth) {
  Camera c;
  for (const auto& e : effects) {
    const double m = e.magnitude;
    if (!std::isfinite(m)) throw UsageError("hidden effect " + e.id + ": magnitude must be finite");
    if (e.id == "landmark_range_scale") {
      c.range_scale = 1.0 + m;
      truth["landmark_range_scale.scale"] = c.range_scale;
    } else if (e.id == "landmark_range_bias") {
      c.range_bias = m;
      truth["landmark_range_bias.bias_m"] = m;
    } else if (e.id == "landmark_range_off_axis_scale") {
      c.off_axis = m;
      truth["landmark_range_off_axis_scale.per_rad"] = 0.1 * m;  // a distortion centred off bearing 0
      truth["landmark_range_off_axis_scale.per_rad2"] = m;
    } else if (e.id == "landmark_bearing_bias") {
      c.bearing_bias = m;
      truth["landmark_bearing_bias.bias_rad"] = m;
    } else if (e.id == "landmark_time_offset") {
      c.offset = m;
      truth["landmark_time_offset.offset_s"] = m;
    } else if (e.id == "landmark_range_dependent_noise") {
      if (m < 0.0) throw UsageError("landmark_range_dependent_noise: the slope must be ≥ 0");
      c.slope = m;
      truth["landmark_range_dependent_noise.slope"] = m;
    } else if (e.id == "landmark_turn_dependent_bearing_noise") {
      if (m < 0.0) throw UsageError("landmark_turn_dependent_bearing_noise: the slope must be ≥ 0");
      c.turn_slope = m;
      truth["landmark_turn_dependent_bearing_noise.slope"] = m;
    } else if (e.id == "landmark_heavy_tails") {
      c.dof = static_cast<int>(std::lround(m));
      if (c.dof < 1) throw UsageError("landmark_heavy_tails: the degrees of freedom must be an integer ≥ 1");
      truth["landmark_heavy_tails.dof"] = c.dof;
    } else if (e.id == "landmark_position_error") {
      c.displaced = static_cast<int>(rng.uniform(0.0, 0.999) * landmarks);
      const double a = rng.uniform(-3.14159, 3.14159);
      c.dx = m * std::cos(a);
      c.dy = m * std::sin(a);
      truth["landmark_position_error.dx_m"] = c.dx;
      truth["landmark_position_error.dy_m"] = c.dy;
    } else {
      throw UsageError("hidden effect: unknown landmark id '" + e.id + "'");
    }
  }
  return c;
}

// Student-t with `dof` degrees of freedom (integer), scale 1; normal for dof 0.
double noise(Rng& rng, int dof) {
  const double z = rng.normal();
  if (dof <= 0) return z;
  double chi2 = 0.0;
  for (int k = 0; k < dof; ++k) {
    const double n = rng.normal();
    chi2 += n * n;
  }
  return z / std::sqrt(chi2 / dof);
}

std::optional<Pose2> pose_at(const std::vector<TruePose>& truth, double t) {
  auto it = std::lower_bound(truth.begin(), truth.end(), t, [](const TruePose& p, double v) { return p.t < v; });
  if (it == truth.begin() || it == truth.end()) return std::nullopt;
  const auto& b = *it;
  const auto& a = *(it - 1);
  const double f = (t - a.t) / (b.t - a.t);
  return Pose2(a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
               a.pose.theta + f * angle_diff(b.pose.theta, a.pose.theta));
}

// Observations of the true landmarks from the poses of `truth` (exact, noise-free).
void observe(GeneratedLog& g, const std::vector<TruePose>& truth, const std::vector<HiddenEffect>& effects,
             std::uint64_t seed, const LandmarkLogOptions& o) {
  Rng rng = Rng::stream(seed, 11);
  std::vector<MapLandmark> real;
  const double lo = -1.0, hi = o.area + 1.0;
  for (int k = 0; k < o.landmarks; ++k) {
    real.push_back({6 + k, rng.uniform(lo, hi), rng.uniform(lo, hi), 1e-4, 1e-4});
  }
  const Camera c = camera_of(effects, o.landmarks, rng, g.truth);
  g.log.landmark_map = real;
  if (c.displaced >= 0) {
    // The survey is off: the map says true − (dx, dy).
    g.log.landmark_map[static_cast<std::size_t>(c.displaced)].x -= c.dx;
    g.log.landmark_map[static_cast<std::size_t>(c.displaced)].y -= c.dy;
  }
  if (truth.size() < 2) return;
  for (double t = truth.front().t + rng.uniform(0.2, 0.4); t < truth.back().t; t += rng.uniform(0.2, 0.4)) {
    const auto p = pose_at(truth, t);
    if (!p) continue;
    std::vector<std::size_t> visible;
    for (std::size_t k = 0; k < real.size(); ++k) {
      const double r = std::hypot(real[k].x - p->x, real[k].y - p->y);
      const double b = angle_diff(std::atan2(real[k].y - p->y, real[k].x - p->x), p->theta);
      if (r >= o.min_range && r <= o.max_range && std::abs(b) <= o.field_of_view) visible.push_back(k);
    }
    if (visible.empty()) continue;
    const std::size_t k = visible[rng.index(visible.size())];
    const double rho = std::hypot(real[k].x - p->x, real[k].y - p->y);
    const double phi = angle_diff(std::atan2(real[k].y - p->y, real[k].x - p->x), p->theta);
    const double sr = std::sqrt(o.sigma_range * o.sigma_range + c.slope * rho * c.slope * rho);
    const auto before = pose_at(truth, t - 0.05), after = pose_at(truth, t + 0.05);
    const double turn_rate = before && after ? angle_diff(after->theta, before->theta) / 0.1 : 0.0;
    const double sb = std::hypot(o.sigma_bearing, c.turn_slope * turn_rate);
    LandmarkReading r;
    r.t = t + c.offset;
    r.subject = real[k].id;
    r.range =
        std::max(0.0, (c.range_scale + c.off_axis * (0.1 + phi) * phi) * rho + c.range_bias + sr * noise(rng, c.dof));
    r.bearing = wrap_angle(phi + c.bearing_bias + sb * noise(rng, c.dof));
    g.log.landmarks.push_back(r);
  }
  // A few observations of another robot (subject 2), which the map does not hold.
  for (std::size_t i = 0; i < g.log.landmarks.size(); i += 50) {
    LandmarkReading r = g.log.landmarks[i];
    r.subject = 2;
    g.log.landmarks.push_back(r);
  }
  std::sort(g.log.landmarks.begin(), g.log.landmarks.end(),
            [](const LandmarkReading& a, const LandmarkReading& b) { return a.t < b.t; });
}

}  // namespace

void add_landmark_observations(GeneratedLog& g, const std::vector<HiddenEffect>& effects, std::uint64_t seed,
                               const LandmarkLogOptions& options) {
  const std::vector<TruePose> truth = g.log.truth;
  g.effects.insert(g.effects.end(), effects.begin(), effects.end());
  observe(g, truth, effects, seed, options);
}

GeneratedLog generate_landmark_log(const std::vector<HiddenEffect>& effects, std::uint64_t seed,
                                   const LandmarkLogOptions& o) {
  Rng rng = Rng::stream(seed, 10);
  GeneratedLog g;
  g.effects = effects;
  g.log.name = "sim/landmark_effects";
  g.log.source = fmt::format("generated-landmarks(seed={})", seed);
  // Legs: turn in place towards a random waypoint, then drive to it.
  std::vector<TruePose> exact;
  Pose2 p(0.5 * o.area, 0.5 * o.area, rng.uniform(-3.14159, 3.14159));
  const double dt = 1.0 / o.truth_rate;
  double t = 0.0;
  auto emit = [&](const Pose2& q) {
    exact.push_back({t, q, q});
    t += dt;
  };
  while (t < o.duration) {
    const double wx = rng.uniform(0.0, o.area), wy = rng.uniform(0.0, o.area);
    const double turn = angle_diff(std::atan2(wy - p.y, wx - p.x), p.theta);
    const int nt = static_cast<int>(std::ceil(std::abs(turn) / (o.turn_rate * dt)));
    for (int k = 0; k < nt && t < o.duration; ++k) emit(Pose2(p.x, p.y, wrap_angle(p.theta + turn * k / nt)));
    p = Pose2(p.x, p.y, wrap_angle(p.theta + turn));
    const double dist = std::hypot(wx - p.x, wy - p.y);
    const int nd = static_cast<int>(std::ceil(dist / (o.speed * dt)));
    for (int k = 0; k < nd && t < o.duration; ++k) {
      const double f = static_cast<double>(k) / nd;
      emit(Pose2(p.x + f * (wx - p.x), p.y + f * (wy - p.y), p.theta));
    }
    p = Pose2(wx, wy, p.theta);
  }
  Rng vicon = Rng::stream(seed, 12);
  for (const auto& e : exact) {
    Pose2 q(e.pose.x + vicon.normal(0.0, o.truth_noise_xy), e.pose.y + vicon.normal(0.0, o.truth_noise_xy),
            wrap_angle(e.pose.theta + vicon.normal(0.0, o.truth_noise_theta)));
    g.log.truth.push_back({e.t, q, Pose2()});
  }
  if (o.odometry) {
    // ODOM at 10 Hz: the true motion's velocities with 1% noise, dead reckoned.
    Pose2 q = exact.front().pose;
    const std::size_t stride = static_cast<std::size_t>(std::max(1.0, std::round(0.1 / dt)));
    for (std::size_t i = 0; i + stride < exact.size(); i += stride) {
      const Pose2& a = exact[i].pose;
      const Pose2& b = exact[i + stride].pose;
      const double h = exact[i + stride].t - exact[i].t;
      const double v = std::hypot(b.x - a.x, b.y - a.y) / h * (1.0 + 0.01 * vicon.normal());
      const double w = angle_diff(b.theta, a.theta) / h * (1.0 + 0.01 * vicon.normal());
      g.log.odometry.push_back({exact[i].t, q, v, w});
      const double mid = q.theta + 0.5 * w * h;
      q = Pose2(q.x + v * h * std::cos(mid), q.y + v * h * std::sin(mid), wrap_angle(q.theta + w * h));
    }
  }
  observe(g, exact, effects, seed, o);
  return g;
}

}  // namespace locbench::sim
