#include "baselines/global/monte_carlo_localization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "baselines/global/options_fields.h"
#include "core/errors.h"
#include "core/units.h"

namespace locbench::baselines::global {

void validate(const MclOptions& o) {
  validate_fields(o, "MclOptions");
  if (o.max_particles < o.min_particles) {
    throw UsageError("MclOptions: need min_particles ≤ max_particles");
  }
  if (!(o.alpha_fast > o.alpha_slow)) throw UsageError("MclOptions: need alpha_slow < alpha_fast");
}

std::size_t kld_sample_count(std::size_t k, double epsilon, double z) {
  if (!(epsilon > 0.0)) throw UsageError("kld_sample_count: epsilon must be > 0");
  if (k <= 1) return 0;
  const double km1 = static_cast<double>(k - 1);
  const double a = 2.0 / (9.0 * km1);
  const double b = 1.0 - a + std::sqrt(a) * z;
  return static_cast<std::size_t>(std::ceil(km1 / (2.0 * epsilon) * b * b * b));
}

std::vector<std::size_t> low_variance_resample(std::span<const double> weights, std::size_t m, Rng& rng) {
  double total = 0.0;
  for (double w : weights) {
    if (!(std::isfinite(w) && w >= 0.0)) throw UsageError("low_variance_resample: bad weight");
    total += w;
  }
  if (!(total > 0.0)) throw UsageError("low_variance_resample: all weights are 0");
  std::vector<std::size_t> out;
  out.reserve(m);
  const double step = total / static_cast<double>(m);
  const double r = rng.uniform() * step;
  double c = weights[0];
  std::size_t i = 0;
  for (std::size_t j = 0; j < m; ++j) {
    const double u = r + static_cast<double>(j) * step;
    while (u > c && i + 1 < weights.size()) c += weights[++i];
    out.push_back(i);
  }
  return out;
}

MonteCarloLocalization::MonteCarloLocalization(const LineMap& map, const MclOptions& options, std::uint64_t seed)
    : options_((validate(options), options)), field_(map, options.field), rng_(seed) {
  init_global();
}

Pose2 MonteCarloLocalization::random_pose() {
  const Bounds& b = field_.bounds();
  return {rng_.uniform(b.min_x, b.max_x), rng_.uniform(b.min_y, b.max_y), rng_.uniform(-kPi, kPi)};
}

void MonteCarloLocalization::init_global() {
  particles_.assign(static_cast<std::size_t>(options_.initial_particles), {});
  for (Particle& p : particles_) p = {random_pose(), 1.0};
  last_odometry_.reset();
  w_slow_ = w_fast_ = 0.0;
  compute_estimate();
}

void MonteCarloLocalization::init_pose(const Pose2& pose, double sigma_xy, double sigma_theta) {
  particles_.assign(static_cast<std::size_t>(options_.max_particles), {});
  for (Particle& p : particles_) {
    p = {Pose2(rng_.normal(pose.x, sigma_xy), rng_.normal(pose.y, sigma_xy), rng_.normal(pose.theta, sigma_theta)),
         1.0};
  }
  last_odometry_.reset();
  w_slow_ = w_fast_ = 0.0;
  compute_estimate();
}

bool MonteCarloLocalization::update(const Pose2& odometry, const Scan& scan) {
  if (last_odometry_) {
    const OdometryDelta d = odometry_delta(*last_odometry_, odometry);
    if (moved_less_than(d, *last_odometry_, odometry, options_.update_min_distance, options_.update_min_angle)) {
      return false;
    }
    for (Particle& p : particles_) p.pose = sample_motion(p.pose, d, options_.motion, rng_);
  }
  last_odometry_ = odometry;
  weigh(scan);
  compute_estimate();
  resample();
  ++updates_;
  return true;
}

void MonteCarloLocalization::weigh(const Scan& scan) {
  const std::vector<Eigen::Vector2d> ends = field_.beam_endpoints(scan);
  double max_log = -std::numeric_limits<double>::infinity();
  std::vector<double> logw(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    logw[i] = field_.log_likelihood(particles_[i].pose, ends);
    max_log = std::max(max_log, logw[i]);
  }
  // Average likelihood per beam (geometric mean over the beams, so it stays in a numerically
  // safe range whatever the beam count) for augmented MCL's w_slow and w_fast.
  double w_avg = 0.0;
  const double beams = std::max<double>(1.0, static_cast<double>(ends.size()));
  double total = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    w_avg += std::exp(logw[i] / beams);
    particles_[i].weight = std::exp(logw[i] - max_log);
    total += particles_[i].weight;
  }
  w_avg /= static_cast<double>(particles_.size());
  for (Particle& p : particles_) p.weight /= total;
  if (ends.empty()) return;  // nothing seen: keep the averages
  w_slow_ += options_.alpha_slow * (w_avg - w_slow_);
  w_fast_ += options_.alpha_fast * (w_avg - w_fast_);
}

namespace {
struct BinKey {
  std::int64_t key;
  bool operator==(const BinKey&) const = default;
};
std::int64_t bin_key(const Pose2& p, const Eigen::Vector3d& bin) {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x / bin(0)));
  const auto iy = static_cast<std::int64_t>(std::floor(p.y / bin(1)));
  const auto it = static_cast<std::int64_t>(std::floor((p.theta + kPi) / bin(2)));
  return (ix & 0xFFFFF) | ((iy & 0xFFFFF) << 20) | ((it & 0xFFFFF) << 40);
}
}  // namespace

void MonteCarloLocalization::resample() {
  std::vector<double> w(particles_.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = particles_[i].weight;
  const std::size_t max_n = static_cast<std::size_t>(options_.max_particles);
  const std::size_t min_n = static_cast<std::size_t>(options_.min_particles);
  std::vector<std::size_t> pool = low_variance_resample(w, max_n, rng_);
  injection_ = options_.inject && w_slow_ > 0.0 ? std::max(0.0, 1.0 - w_fast_ / w_slow_) : 0.0;
  std::vector<Particle> next;
  next.reserve(max_n);
  std::unordered_map<std::int64_t, int> bins;
  std::size_t bound = max_n;
  for (std::size_t n = 0; n < max_n; ++n) {
    if (options_.kld) {
      // Fisher–Yates step: a random not-yet-taken element of the low-variance pool.
      const std::size_t j = n + static_cast<std::size_t>(rng_.uniform() * static_cast<double>(max_n - n));
      std::swap(pool[n], pool[std::min(j, max_n - 1)]);
    }
    Pose2 p = particles_[pool[n]].pose;
    if (injection_ > 0.0 && rng_.bernoulli(injection_)) p = random_pose();
    next.push_back({p, 1.0});
    if (options_.kld) {
      if (++bins[bin_key(p, options_.kld_bin)] == 1) {
        bound = std::min(max_n, std::max(min_n, kld_sample_count(bins.size(), options_.kld_epsilon, options_.kld_z)));
      }
      if (next.size() >= bound && next.size() >= min_n) break;
    }
  }
  const double uniform = 1.0 / static_cast<double>(next.size());
  for (Particle& p : next) p.weight = uniform;
  particles_ = std::move(next);
}

void MonteCarloLocalization::compute_estimate() {
  // The heaviest histogram bin, then the weighted mean of the particles in it and its 26
  // neighbours (headings by their circular mean).
  const Eigen::Vector3d& bin = options_.kld_bin;
  std::unordered_map<std::int64_t, double> mass;
  double best = -1.0;
  std::int64_t best_key = 0;
  for (const Particle& p : particles_) {
    const std::int64_t k = bin_key(p.pose, bin);
    const double m = (mass[k] += p.weight);
    if (m > best) {
      best = m;
      best_key = k;
    }
  }
  const auto unpack = [](std::int64_t k, int shift) {
    std::int64_t v = (k >> shift) & 0xFFFFF;
    if (v & 0x80000) v -= 0x100000;
    return v;
  };
  const std::int64_t bx = unpack(best_key, 0), by = unpack(best_key, 20), bt = unpack(best_key, 40);
  const std::int64_t nt = static_cast<std::int64_t>(std::ceil(2.0 * kPi / bin(2)));
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0, sw = 0.0;
  for (const Particle& p : particles_) {
    const std::int64_t k = bin_key(p.pose, bin);
    const std::int64_t dt = std::abs(unpack(k, 40) - bt);
    if (std::abs(unpack(k, 0) - bx) > 1 || std::abs(unpack(k, 20) - by) > 1 || std::min(dt, nt - dt) > 1) {
      continue;
    }
    sx += p.weight * p.pose.x;
    sy += p.weight * p.pose.y;
    sc += p.weight * std::cos(p.pose.theta);
    ss += p.weight * std::sin(p.pose.theta);
    sw += p.weight;
  }
  if (sw > 0.0) estimate_ = Pose2(sx / sw, sy / sw, std::atan2(ss, sc));
}

std::size_t MonteCarloLocalization::memory_bytes() const {
  return particles_.capacity() * sizeof(Particle) + field_.memory_bytes();
}

}  // namespace locbench::baselines::global
