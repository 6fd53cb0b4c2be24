#pragma once
// Monte Carlo localization (particle filter; slides "随机采样 / 粒子滤波", Thrun et al.,
// Probabilistic Robotics ch. 8) with the odometry action model and the likelihood-field
// perception model, and three additions:
//  * low-variance (systematic) resampling: one random offset r ∈ [0, 1/M), picks r + m/M;
//  * KLD-sampling (Fox 2003): the number of particles n is the smallest with
//      n ≥ (k − 1)/(2ε) · {1 − 2/(9(k − 1)) + √(2/(9(k − 1))) z_{1−δ}}³
//    where k is the number of histogram bins (x, y, θ) the new particles occupy, so that the
//    K-L distance between the sample-based and the true posterior is ≤ ε with probability 1 − δ.
//    Particles are taken one at a time in random order from a low-variance pool of
//    max_particles picks until n reaches the bound (each pick is marginally a draw from the
//    weights, so the set stays unbiased);
//  * random-particle injection (augmented MCL, Table 8.3): short- and long-term averages
//    w_fast, w_slow of the measurement likelihood; each new particle is drawn uniformly over the
//    map with probability max(0, 1 − w_fast/w_slow) — the recovery from a kidnapping.
// The filter updates only after the odometry moved update_min_distance or turned
// update_min_angle since the last update (as AMCL does), so a standing robot does not
// over-commit to one scan.
#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <vector>

#include "baselines/global/likelihood_field.h"
#include "baselines/global/odometry_motion_model.h"
#include "core/line_map.h"
#include "core/rng.h"

namespace locbench::baselines::global {

struct MclOptions {
  OdometryMotionOptions motion;
  LikelihoodFieldOptions field;
  int initial_particles = 5000;  // drawn uniformly for global localization
  int min_particles = 100;
  int max_particles = 5000;
  bool kld = true;                                 // false: keep max_particles
  double kld_epsilon = 0.05;                       // ε, the K-L bound
  double kld_z = 2.326;                            // z_{1−δ}: upper 1 − δ standard normal quantile (δ = 0.01)
  Eigen::Vector3d kld_bin{0.25, 0.25, 0.1745329};  // histogram bin (x, y, θ) [m, m, rad]
  bool inject = true;                              // augmented MCL
  double alpha_slow = 0.001;
  double alpha_fast = 0.1;
  double update_min_distance = 0.10;    // [m]
  double update_min_angle = 0.0872665;  // [rad] (5°)
};
void to_json(nlohmann::json& j, const MclOptions& o);
void from_json(const nlohmann::json& j, MclOptions& o);  // strict; UsageError
void validate(const MclOptions& o);

// KLD-sampling's sample count for k occupied bins (Fox 2003, eq. 12, Wilson–Hilferty
// approximation of the χ² quantile): ⌈(k − 1)/(2ε) · (1 − 2/(9(k − 1)) + √(2/(9(k − 1))) z)³⌉,
// 0 for k ≤ 1. UsageError for ε ≤ 0.
std::size_t kld_sample_count(std::size_t k, double epsilon, double z);

// Low-variance resampling (Probabilistic Robotics Table 4.4): m indices into `weights`
// (non-negative, not all 0; need not sum to 1), in ascending order. UsageError otherwise.
std::vector<std::size_t> low_variance_resample(std::span<const double> weights, std::size_t m, Rng& rng);

struct Particle {
  Pose2 pose;
  double weight = 1.0;
};

class MonteCarloLocalization {
 public:
  // UsageError for invalid options or an empty map. Starts with a global (uniform) belief.
  MonteCarloLocalization(const LineMap& map, const MclOptions& options, std::uint64_t seed);

  // initial_particles poses uniform over the map's bounding box, headings uniform.
  void init_global();
  // Particles around a known pose (position σ, heading σ).
  void init_pose(const Pose2& pose, double sigma_xy, double sigma_theta);
  // One odometry pose (odometry frame) and the scan taken there. Returns true when the filter
  // updated (moved enough since the last update, or the first scan).
  bool update(const Pose2& odometry, const Scan& scan);

  Pose2 estimate() const { return estimate_; }
  const std::vector<Particle>& particles() const { return particles_; }
  std::size_t particle_count() const { return particles_.size(); }
  // Fraction of particles injected at random in the last update.
  double injection_probability() const { return injection_; }
  std::size_t updates() const { return updates_; }
  // Particles, weights and the likelihood field.
  std::size_t memory_bytes() const;
  const LikelihoodField& field() const { return field_; }

 private:
  void weigh(const Scan& scan);
  void resample();
  void compute_estimate();
  Pose2 random_pose();

  MclOptions options_;
  LikelihoodField field_;
  Rng rng_;
  std::vector<Particle> particles_;
  std::optional<Pose2> last_odometry_;
  Pose2 estimate_;
  double w_slow_ = 0.0, w_fast_ = 0.0, injection_ = 0.0;
  std::size_t updates_ = 0;
};

}  // namespace locbench::baselines::global
