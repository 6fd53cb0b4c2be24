#include "pipelines/landmark_twin.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/angle.h"
#include "core/errors.h"
#include "core/rng.h"

namespace locbench::experiments::landmarks {
namespace {

constexpr double kTwinTruthMargin = 2.0;  // [s] the truth held still beyond the span's ends

diagnosis::MotionWindow block(const diagnosis::MotionData& d, std::size_t first, std::size_t last) {
  diagnosis::MotionWindow w;
  w.first = first;
  w.last = last;
  w.t0 = d.steps[first].t0;
  w.t1 = d.steps[last - 1].t1;
  return w;
}

// Appends the truth over steps [w.first, w.last) from `start` (true time = logged − offset): the
// model's partial predictions, the stall's loss and `noise` (the window's residual) spread in
// proportion to time. Returns the pose at the block's end.
Pose2 walk_block(const diagnosis::MotionData& d, const diagnosis::MotionWindow& w,
                 const diagnosis::OdometryModel& mean_model, double keep, const Eigen::Vector3d& noise,
                 const Pose2& start, std::vector<TruePose>& truth) {
  const double span = w.t1 - w.t0;
  Pose2 end = start;
  for (std::size_t k = w.first; k < w.last; ++k) {
    const Pose2 p = diagnosis::predict_window(d, block(d, w.first, k + 1), mean_model);
    const double f = span > 0.0 ? (d.steps[k].t1 - w.t0) / span : 1.0;
    end = start * Pose2(keep * p.x + f * noise.x(), keep * p.y + f * noise.y(), p.theta + f * noise.z());
    truth.push_back({d.steps[k].t1 - mean_model.time_offset, end, {}});
  }
  return end;
}

// How the twin's commands are steered toward the log's path (landmark_twin): a window that moves
// less than kMinSteerDistance and turns less than kMinSteerTurn stands and is not steered; the
// cross-track error is aimed at over kSteerLookahead; a window's correction is at most half its own
// distance, and half its own turn plus kMaxSteerTurn.
constexpr double kSteerLookahead = 1.0;     // [m]
constexpr double kMinSteerDistance = 0.01;  // [m]
constexpr double kMinSteerTurn = 0.02;      // [rad]
constexpr double kMaxSteerTurn = 0.05;      // [rad]

// Steers the commands (pose odometry) of window `w` of `m`: `e` is the log's true pose in the frame
// of the twin's, both at the window's start, and g = min(1, T/follow_time_s) of it is asked of the
// window beyond its own commands, in the model's units (÷ its velocity and turn-rate scales): g·e_x
// along the track, spread over the steps in proportion to their distance, and a turn
// g·(e_θ + atan2(±e_y, kSteerLookahead)) (the cross-track term when the window drives; its sign
// follows the direction of travel), spread over the moving steps in proportion to their time. The
// window's covariates are refreshed.
void steer_window(diagnosis::MotionData& m, diagnosis::MotionWindow& w, const Pose2& e,
                  const diagnosis::OdometryModel& model, double follow_time_s) {
  double moved = 0.0, signed_moved = 0.0, turned = 0.0, moving_time = 0.0;
  for (std::size_t k = w.first; k < w.last; ++k) {
    const diagnosis::OdometryStep& s = m.steps[k];
    moved += std::abs(s.a);
    signed_moved += s.a;
    turned += std::abs(s.b);
    if (s.a != 0.0 || s.b != 0.0) moving_time += s.t1 - s.t0;
  }
  if ((moved < kMinSteerDistance && turned < kMinSteerTurn) || !(moving_time > 0.0)) return;
  const double g = std::min(1.0, (w.t1 - w.t0) / follow_time_s);
  const double along = std::clamp(g * e.x / model.velocity_scale, -0.5 * moved, 0.5 * moved);
  const double cross = moved >= kMinSteerDistance ? std::atan2(signed_moved < 0.0 ? -e.y : e.y, kSteerLookahead) : 0.0;
  const double cap = 0.5 * turned + kMaxSteerTurn;
  const double turn = std::clamp(g * wrap_angle(e.theta + cross) / model.turn_rate_scale, -cap, cap);
  for (std::size_t k = w.first; k < w.last; ++k) {
    diagnosis::OdometryStep& s = m.steps[k];
    if (s.a == 0.0 && s.b == 0.0) continue;
    if (moved > 0.0) s.a += along * std::abs(s.a) / moved;
    s.b += turn * (s.t1 - s.t0) / moving_time;
  }
  diagnosis::fill_covariates(m, w);
}

// Unit-variance sensor noise with a share of it correlated in time (NoiseCorrelation): the white
// part Student-t (normal for dof 0), the shared part a stationary Gauss–Markov process,
// b ← e^(−Δt/τ)·b + √(1 − e^(−2Δt/τ))·N(0, 1).
class CorrelatedPart {
 public:
  explicit CorrelatedPart(const NoiseCorrelation& c) : c_(c) {}
  double draw(double t, double dof, Rng& rng) {
    const double white = rng.student_t(dof);
    if (!(c_.share > 0.0 && c_.time_s > 0.0)) return white;
    if (!started_) {
      b_ = rng.normal();
      started_ = true;
    } else {
      const double a = std::exp(-std::max(t - t_, 0.0) / c_.time_s);
      b_ = a * b_ + std::sqrt(1.0 - a * a) * rng.normal();
    }
    t_ = t;
    return std::sqrt(1.0 - c_.share) * white + std::sqrt(c_.share) * b_;
  }

 private:
  NoiseCorrelation c_;
  bool started_ = false;
  double t_ = 0.0, b_ = 0.0;
};

// How far the log's camera sees: the widest bearing and the longest range among its observations.
struct CameraReach {
  double bearing = 0.0, range = 0.0;
};
CameraReach camera_reach(const std::vector<Observation>& observations) {
  CameraReach c;
  for (const Observation& o : observations) {
    c.bearing = std::max(c.bearing, std::abs(o.bearing));
    c.range = std::max(c.range, o.range);
  }
  return c;
}

// The schedule the twin's camera keeps: each frame of the log (observations sharing a time) looks
// at the same time, from the twin's pose then, and sees as many landmarks as the log's frame saw.
// A landmark the log saw is seen again when it is within the camera's reach from the twin's pose;
// each one that is not gives way to another landmark within reach, drawn at random among those the
// frame does not see yet (none left: the frame sees fewer). Without this the twin's camera would
// see the log's landmarks wherever its drifted pose put them — on MRCLAM Dataset 6, 29–75% of them
// beyond the widest bearing the real camera ever reported.
std::vector<Observation> visible_schedule(const TrackingData& real, diagnosis::TruthInterpolator& at,
                                          const LandmarkSensorModel& sensor, Rng& rng) {
  const CameraReach reach = camera_reach(real.observations);
  const auto sees = [&](const Pose2& p, int id) {
    Eigen::Vector2d l = real.map.at(id);
    if (const auto s = sensor.landmark_shift.find(id); s != sensor.landmark_shift.end()) l += s->second;
    const double phi = wrap_angle(std::atan2(l.y() - p.y, l.x() - p.x) - p.theta);
    return std::abs(phi) <= reach.bearing && std::hypot(l.x() - p.x, l.y() - p.y) <= reach.range;
  };
  std::vector<Observation> out;
  out.reserve(real.observations.size());
  const auto& obs = real.observations;
  for (std::size_t i = 0, j = 0; i < obs.size(); i = j) {
    j = i + 1;
    while (j < obs.size() && obs[j].t == obs[i].t) ++j;  // the frame: [i, j)
    const auto p = at.at(obs[i].t - sensor.time_offset);
    if (!p) continue;
    std::vector<int> seen, free;
    for (std::size_t k = i; k < j; ++k)
      if (sees(*p, obs[k].id) && std::find(seen.begin(), seen.end(), obs[k].id) == seen.end())
        seen.push_back(obs[k].id);
    for (const auto& [id, position] : real.map)
      if (std::find(seen.begin(), seen.end(), id) == seen.end() && sees(*p, id)) free.push_back(id);
    for (std::size_t k = i; k < j; ++k) {
      Observation o = obs[k];
      if (std::find(seen.begin(), seen.end(), o.id) == seen.end()) {
        if (free.empty()) continue;
        const std::size_t pick = rng.index(free.size());
        o.id = free[pick];
        free.erase(free.begin() + static_cast<std::ptrdiff_t>(pick));
      }
      out.push_back(o);
    }
  }
  return out;
}

// A block with fewer windows says little about its rate.
constexpr std::size_t kMinBiasBlockWindows = 10;

// The spread of the heading residual's rate between blocks of kLevelBlockS beyond the windows'
// own noise. Per block b (≥ kMinBiasBlockWindows windows): its rate m_b = Σ r_θ / Σ Δt, and the variance the model
// expects of it, Σ_ij √(v_i·v_j)·c·((1 − s)·δ_ij + s·e^(−|t_i − t_j|/τ)) / (Σ Δt)², with v the
// windows' model variances, (s, τ) the fitted correlation and c the residuals' own scale about
// their block's rate, Σ (r_i − m_b·Δt_i)²/v_i / (N − B). The excess is the variance of the m_b
// (about their Δt-weighted mean) less the mean expected one.
double turn_bias_spread(const std::vector<double>& t, const std::vector<double>& span, const std::vector<double>& r,
                        const std::vector<double>& v, const NoiseCorrelation& c) {
  struct Block {
    std::size_t first, last;
    double rate, duration;
  };
  std::vector<Block> blocks;
  for (std::size_t i = 0, j = 0; i < t.size(); i = j) {
    double sum = 0.0, duration = 0.0;
    for (j = i; j < t.size() && t[j] < t[i] + kLevelBlockS; ++j) {
      sum += r[j];
      duration += span[j];
    }
    if (j - i >= kMinBiasBlockWindows && duration > 0.0) blocks.push_back({i, j, sum / duration, duration});
  }
  if (blocks.size() < 3) return 0.0;
  double scale = 0.0, count = 0.0;
  for (const Block& b : blocks) {
    for (std::size_t a = b.first; a < b.last; ++a) {
      const double about_rate = r[a] - b.rate * span[a];
      scale += about_rate * about_rate / v[a];
    }
    count += static_cast<double>(b.last - b.first) - 1.0;
  }
  scale /= count;
  double total = 0.0, mean = 0.0, model = 0.0;
  for (const Block& b : blocks) {
    mean += b.duration * b.rate;
    total += b.duration;
    double variance = 0.0;
    for (std::size_t a = b.first; a < b.last; ++a) {
      for (std::size_t k = b.first; k < b.last; ++k) {
        const double shared =
            c.share > 0.0 && c.time_s > 0.0 ? c.share * std::exp(-std::abs(t[a] - t[k]) / c.time_s) : 0.0;
        variance += std::sqrt(v[a] * v[k]) * scale * ((a == k ? 1.0 - c.share : 0.0) + shared);
      }
    }
    model += variance / (b.duration * b.duration);
  }
  mean /= total;
  double spread = 0.0;
  for (const Block& b : blocks) spread += (b.rate - mean) * (b.rate - mean);
  const double n = static_cast<double>(blocks.size());
  return std::sqrt(std::max(spread / (n - 1.0) - model / n, 0.0));
}

// The observations of `real`'s schedule (visible_schedule) drawn from `sensor` as seen from the
// truth `at`: the noise and each landmark's bias from `rng`, the schedule's substitutes and the
// gross outliers from `camera`.
std::vector<Observation> draw_observations(const TrackingData& real, diagnosis::TruthInterpolator& at,
                                           const LandmarkSensorModel& sensor, Rng& rng, Rng& camera) {
  std::vector<Observation> out;
  CorrelatedPart range_part(sensor.structure.range_correlation), bearing_part(sensor.structure.bearing_correlation);
  std::map<int, std::pair<double, double>> landmark_bias;  // drawn per twin: range, bearing
  for (const auto& [id, position] : real.map) {
    landmark_bias[id] = {sensor.structure.range_landmark_sigma * rng.normal(),
                         sensor.structure.bearing_landmark_sigma * rng.normal()};
  }
  // Noise levels that vary along the log: one factor per block of kLevelBlockS, e^(s·N(0, 1)).
  std::map<long, std::pair<double, double>> level;  // block → range, bearing factors
  const auto level_at = [&](double t) {
    const long b = static_cast<long>(std::floor((t - real.from) / kLevelBlockS));
    auto it = level.find(b);
    if (it == level.end()) {
      const double fr = std::exp(sensor.structure.range_level_sigma * rng.normal());
      const double fb = std::exp(sensor.structure.bearing_level_sigma * rng.normal());
      it = level.emplace(b, std::pair{fr, fb}).first;
    }
    return it->second;
  };
  for (const Observation& o : visible_schedule(real, at, sensor, camera)) {
    const auto p = at.at(o.t - sensor.time_offset);
    if (!p) continue;
    Eigen::Vector2d l = real.map.at(o.id);
    if (const auto s = sensor.landmark_shift.find(o.id); s != sensor.landmark_shift.end()) l += s->second;
    const double rho = std::hypot(l.x() - p->x, l.y() - p->y);
    const double phi = std::atan2(l.y() - p->y, l.x() - p->x) - p->theta;
    const double sigma_r = std::hypot(sensor.range_sigma, sensor.range_noise_slope * rho);
    const auto before = at.at(o.t - sensor.time_offset - 0.05), after = at.at(o.t - sensor.time_offset + 0.05);
    const double turn_rate = before && after ? angle_diff(after->theta, before->theta) / 0.1 : 0.0;
    const double sigma_b = std::hypot(sensor.bearing_sigma, sensor.bearing_noise_turn_slope * turn_rate);
    Observation z = o;
    const auto [range_bias, bearing_bias] = landmark_bias.at(o.id);
    const bool varies = sensor.structure.range_level_sigma > 0.0 || sensor.structure.bearing_level_sigma > 0.0;
    const auto [range_level, bearing_level] = varies ? level_at(o.t) : std::pair{1.0, 1.0};
    z.range = sensor.range_scale_at(wrap_angle(phi)) * rho + sensor.range_bias + range_bias +
              range_level * sigma_r * range_part.draw(o.t, sensor.dof, rng);
    z.bearing = wrap_angle(phi + sensor.bearing_bias + bearing_bias +
                           bearing_level * sigma_b * bearing_part.draw(o.t, sensor.dof, rng));
    // A gross outlier instead of the noise (drawn above all the same, so that the noise streams
    // stay the same with and without outliers).
    const std::vector<Eigen::Vector2d>& outliers = sensor.structure.outliers;
    if (!outliers.empty() && camera.bernoulli(sensor.structure.outlier_rate)) {
      const Eigen::Vector2d& e = outliers[camera.index(outliers.size())];
      z.range = sensor.range_scale_at(wrap_angle(phi)) * rho + sensor.range_bias + e.x() * sigma_r;
      z.bearing = wrap_angle(phi + sensor.bearing_bias + e.y());
    }
    out.push_back(z);
  }
  return out;
}

}  // namespace

MotionNoiseStructure fit_motion_noise_structure(const diagnosis::MotionData& data,
                                                const diagnosis::OdometryModel& model) {
  std::vector<double> t, x, y, theta, span, heading, heading_variance;
  std::vector<bool> adjacent;  // the window kept before is the one just before, without a gap
  bool previous_kept = false;
  std::size_t previous_last = 0;
  for (const diagnosis::MotionWindow& w : data.windows) {
    const diagnosis::WindowResidual r = diagnosis::window_residual(data, w, model);
    const bool follows = previous_kept && w.first == previous_last;
    previous_last = w.last;
    previous_kept = r.valid && !r.heading_only;
    if (!previous_kept) continue;
    adjacent.push_back(follows);
    t.push_back(w.t0);
    x.push_back(r.r.x() / std::sqrt(r.variance.x()));
    y.push_back(r.r.y() / std::sqrt(r.variance.y()));
    theta.push_back(r.r.z() / std::sqrt(r.variance.z()));
    span.push_back(w.t1 - w.t0);
    heading.push_back(r.r.z());
    heading_variance.push_back(r.variance.z());
  }
  MotionNoiseStructure s{fit_noise_correlation(t, x), fit_noise_correlation(t, y), fit_noise_correlation(t, theta),
                         large_residual_runs(x, adjacent)};
  s.turn_bias_spread = turn_bias_spread(t, span, heading, heading_variance, s.theta);
  s.level_spread = {noise_level_spread(t, x), noise_level_spread(t, y), noise_level_spread(t, theta)};
  const std::vector<std::optional<double>> stalled = diagnosis::stall_posteriors(data, model);
  double together = 0.0, first = 0.0;
  for (std::size_t k = 0; k + 1 < data.windows.size(); ++k) {
    if (data.windows[k + 1].first != data.windows[k].last || !stalled[k] || !stalled[k + 1]) continue;
    together += *stalled[k] * *stalled[k + 1];
    first += *stalled[k];
  }
  if (first >= kMinStallWindows) s.stall_persistence = std::clamp(together / first, 0.0, kMaxStallPersistence);
  return s;
}

TrackingData landmark_twin(const TrackingData& real, const diagnosis::OdometryModel& motion,
                           const LandmarkSensorModel& sensor, std::uint64_t seed, const MotionNoiseStructure& structure,
                           double follow_time_s) {
  const diagnosis::MotionData& d = real.motion;
  if (d.windows.empty() || d.steps.empty()) throw InputError(real.log, 0, "the twin needs the span's motion windows");
  const auto first = diagnosis::interpolate_truth(d.truth, d.steps.front().t0 - motion.time_offset);
  const Pose2 origin = first ? *first : d.truth.empty() ? Pose2() : d.truth.front().pose;
  if (!first && d.truth.empty()) throw InputError(real.log, 0, "no truth at the span's start for the twin");

  Rng rng(seed);
  diagnosis::OdometryModel mean_model = motion;  // the stalls are drawn, not averaged
  mean_model.stall_rate = 0.0;
  mean_model.stall_duration = 0.0;

  TrackingData twin = real;
  diagnosis::MotionData& m = twin.motion;  // the twin's commands: the log's, steered when follow_time_s > 0
  const bool steers = follow_time_s > 0.0 && m.odometry == diagnosis::OdometryKind::kPose;
  std::vector<TruePose>& truth = m.truth;
  truth.clear();
  const double t_start = d.steps.front().t0 - motion.time_offset;
  truth.push_back({t_start - kTwinTruthMargin, origin, {}});
  truth.push_back({t_start, origin, {}});
  Pose2 pose = origin;
  CorrelatedPart along(structure.x), left(structure.y), turn(structure.theta);
  // The turn-rate bias that moves along the log: a new one per block of kLevelBlockS, on a stream
  // of its own (the other draws stay those of a twin without it).
  Rng bias_rng(Rng::derive_seed(seed, 2));
  double bias = 0.0, bias_block_end = -std::numeric_limits<double>::infinity();
  // The motion noise level that moves along the log: one draw per block of kLevelBlockS, on a
  // stream of its own.
  Rng level_rng(Rng::derive_seed(seed, 3));
  long level_block = std::numeric_limits<long>::min();
  double level = 0.0;
  const bool levels = structure.level_spread.maxCoeff() > 0.0;
  std::size_t next = 0;  // first step not walked yet
  bool stalled = false;  // the previous window held a stall
  for (diagnosis::MotionWindow& w : m.windows) {
    if (w.first > next)
      pose = walk_block(m, block(m, next, w.first), mean_model, 1.0, Eigen::Vector3d::Zero(), pose, truth);
    if (steers)
      if (const auto on_path = diagnosis::interpolate_truth(d.truth, w.t0 - motion.time_offset))
        steer_window(m, w, between(pose, *on_path), motion, follow_time_s);
    const Eigen::Vector3d v = diagnosis::window_variance(m, w, motion);
    Eigen::Vector3d r(std::sqrt(v.x()) * along.draw(w.t0, motion.dof, rng),
                      std::sqrt(v.y()) * left.draw(w.t0, motion.dof, rng),
                      std::sqrt(v.z()) * turn.draw(w.t0, motion.dof, rng));
    if (levels) {
      const auto b = static_cast<long>(std::floor((w.t0 - m.windows.front().t0) / kLevelBlockS));
      if (b != level_block) {
        level_block = b;
        level = level_rng.normal();
      }
      for (int c = 0; c < 3; ++c) r(c) *= std::exp(structure.level_spread(c) * level);
    }
    if (structure.turn_bias_spread > 0.0) {
      if (w.t0 >= bias_block_end) {
        bias = structure.turn_bias_spread * bias_rng.normal();
        bias_block_end = w.t0 + kLevelBlockS;
      }
      r.z() += bias * (w.t1 - w.t0);
    }
    double keep = 1.0;
    const double length = w.t1 - w.t0;
    if (const diagnosis::StallOdds odds = diagnosis::window_stall_odds(motion, length); odds.p > 0.0) {
      // A two-state chain with the mixture's p as its stationary probability: after a stall the
      // next window stalls with q, after none with p·(1 − q)/(1 − p) (independent when q ≤ p).
      const double p = odds.p, q = structure.stall_persistence;
      stalled = rng.bernoulli(q <= p ? p : stalled ? q : p * (1.0 - q) / (1.0 - p));
      if (stalled) keep = 1.0 - odds.fraction;
    }
    pose = walk_block(m, w, mean_model, keep, r, pose, truth);
    next = w.last;
  }
  if (next < m.steps.size())
    pose = walk_block(m, block(m, next, m.steps.size()), mean_model, 1.0, Eigen::Vector3d::Zero(), pose, truth);
  truth.push_back({truth.back().t + kTwinTruthMargin, pose, {}});

  diagnosis::TruthInterpolator at(truth);
  Rng camera(Rng::derive_seed(seed, 1));
  twin.observations = draw_observations(real, at, sensor, rng, camera);
  return twin;
}

TrackingData landmark_sensor_twin(const TrackingData& real, const LandmarkSensorModel& sensor, std::uint64_t seed) {
  if (real.motion.truth.empty()) throw InputError(real.log, 0, "the sensor twin needs the span's truth");
  TrackingData twin = real;
  diagnosis::TruthInterpolator at(twin.motion.truth);
  Rng rng(seed), camera(Rng::derive_seed(seed, 1));
  twin.observations = draw_observations(real, at, sensor, rng, camera);
  return twin;
}

}  // namespace locbench::experiments::landmarks
