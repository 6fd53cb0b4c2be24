#pragma once
// Grid Markov localization (slides, "实例研究 2 – 栅格地图"; Burgard et al. 1996, Fox et al.
// 1999): the belief is a histogram over a fixed decomposition of (x, y, θ) — the slides quote
// 15 cm × 15 cm × 1° — updated by
//   action      P(l_t | o_t) = Σ_{l'} P(l_t | l', o_t) P(l')
//   perception  P(l | i) = p(i | l) P(l) / p(i)
// The action update moves every cell's mass by the odometry's (δrot1, δtrans, δrot2) from the
// cell centre, splats it bilinearly in (x, y) and linearly in θ onto the neighbouring cells,
// then blurs with a separable Gaussian whose σ comes from the odometry motion model (isotropic
// in x, y: σ_xy² = σ_trans² + (δtrans σ_rot1)²). The perception update evaluates the
// likelihood field at every cell centre (end points rotated once per θ slice). After each
// perception update a fraction `uniform_mix` of the mass is spread uniformly, the grid's
// counterpart of MCL's random particles ("any pose keeps a non-zero chance").
// Memory: 2 × cells × 8 bytes (belief + scratch) + the likelihood field; time per update is
// linear in the cells (× beams for the perception update).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "baselines/global/likelihood_field.h"
#include "baselines/global/odometry_motion_model.h"
#include "core/line_map.h"

namespace locbench::baselines::global {

struct GridMarkovOptions {
  OdometryMotionOptions motion;
  LikelihoodFieldOptions field;
  double cell_size = 0.20;              // [m] (the slides: 0.15)
  double angular_cell = 0.0872665;      // [rad] (5°; the slides: 1°)
  double update_min_distance = 0.20;    // [m]: odometry accumulated between updates
  double update_min_angle = 0.1745329;  // [rad] (10°)
  double prune_threshold = 1e-9;        // cells below this × the maximum are not moved
  double uniform_mix = 1e-3;            // mass spread uniformly after each perception update
  double max_cells = 1e7;               // refuse larger grids (memory; limits::kGridMarkovCells)
};
void to_json(nlohmann::json& j, const GridMarkovOptions& o);
void from_json(const nlohmann::json& j, GridMarkovOptions& o);  // strict; UsageError
void validate(const GridMarkovOptions& o);

class GridMarkov {
 public:
  // The grid spans the map's bounding box. UsageError for invalid options, an empty map or more
  // than max_cells cells. Starts uniform.
  GridMarkov(const LineMap& map, const GridMarkovOptions& options);

  void init_global();  // uniform
  // All mass in the cell holding `pose` (tracking from a known start).
  void init_pose(const Pose2& pose);
  // Returns true when the filter updated (first scan, or moved enough since the last update).
  bool update(const Pose2& odometry, const Scan& scan);
  void action_update(const OdometryDelta& d);
  void perception_update(const Scan& scan);

  // The most probable cell, refined by the mean of its 3 × 3 × 3 neighbourhood.
  Pose2 estimate() const;
  // Probability mass within `radius` [m] and `angle` [rad] of a pose.
  double mass_near(const Pose2& p, double radius, double angle) const;
  std::size_t cell_count() const { return belief_.size(); }
  int cells_x() const { return nx_; }
  int cells_y() const { return ny_; }
  int cells_theta() const { return nt_; }
  std::size_t memory_bytes() const;
  std::size_t updates() const { return updates_; }
  const std::vector<double>& belief() const { return belief_; }
  Pose2 cell_pose(std::size_t index) const;

 private:
  std::size_t index(int ix, int iy, int it) const {
    return (static_cast<std::size_t>(it) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(iy)) *
               static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(ix);
  }
  void blur(double sigma_xy_cells, double sigma_theta_cells);
  void normalise();

  GridMarkovOptions options_;
  LikelihoodField field_;
  double x0_ = 0.0, y0_ = 0.0;
  int nx_ = 0, ny_ = 0, nt_ = 0;
  std::vector<double> belief_;
  std::vector<double> scratch_;
  std::optional<Pose2> last_odometry_;
  std::size_t updates_ = 0;
};

}  // namespace locbench::baselines::global
