#pragma once
// The likelihood-field perception model for a laser against a line map (Probabilistic Robotics
// §6.4): the end point of each used beam, placed in the world from the hypothesised pose, has
// distance d to the nearest map segment and
//   p(z_k | x, m) = z_hit · N(d; 0, σ_hit²) + z_random / z_max
// (returns at the maximum range are skipped). The distance is looked up in a grid precomputed
// over the map's bounding box plus a margin; points outside it count as d = max_distance.
// log p(z | x, m) = Σ_k log p(z_k | x, m) is precomputed per cell, so one beam costs one load.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/line_map.h"
#include "core/pose2.h"
#include "core/scan.h"

namespace locbench::baselines::global {

struct LikelihoodFieldOptions {
  double resolution = 0.05;   // distance-grid cell [m]
  double max_distance = 1.0;  // distances are clamped here [m]
  double sigma_hit = 0.20;    // [m]: range noise plus map and pose discretisation (wide: a
                              // peaked likelihood makes global localization converge early and wrong)
  double z_hit = 0.9;
  double z_random = 0.1;
  double z_max = 8.0;   // range of the uniform random-return density [m]
  double margin = 1.0;  // grid extends this far beyond the map's bounding box [m]
  int beams = 20;       // beams used per scan, evenly spread over the valid ones
};
void to_json(nlohmann::json& j, const LikelihoodFieldOptions& o);
void from_json(const nlohmann::json& j, LikelihoodFieldOptions& o);  // strict; UsageError
void validate(const LikelihoodFieldOptions& o);

struct Bounds {
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
};
// Bounding box of a map's segments; UsageError for an empty map.
Bounds map_bounds(const LineMap& map);

class LikelihoodField {
 public:
  // UsageError for invalid options or an empty map.
  LikelihoodField(const LineMap& map, const LikelihoodFieldOptions& options);

  // Distance from (x, y) to the nearest segment, as stored in the grid (clamped).
  double distance(double x, double y) const;
  // log p(z_k | ·) of one end point in the world.
  double log_beam(double x, double y) const {
    const int cx = static_cast<int>(std::floor((x - origin_x_) * inv_res_));
    const int cy = static_cast<int>(std::floor((y - origin_y_) * inv_res_));
    if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return log_far_;
    return log_p_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx)];
  }
  // The end points of the beams used from `scan`, in the robot frame (mount applied).
  std::vector<Eigen::Vector2d> beam_endpoints(const Scan& scan) const;
  // Σ_k log p(z_k | robot, m) for end points in the robot frame.
  double log_likelihood(const Pose2& robot, const std::vector<Eigen::Vector2d>& endpoints) const;

  const Bounds& bounds() const { return map_bounds_; }  // the map's own box, no margin
  const LikelihoodFieldOptions& options() const { return options_; }
  std::size_t memory_bytes() const { return log_p_.size() * sizeof(float); }
  int cells_x() const { return nx_; }
  int cells_y() const { return ny_; }

 private:
  LikelihoodFieldOptions options_;
  Bounds map_bounds_;
  double origin_x_ = 0.0, origin_y_ = 0.0, inv_res_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<float> distance_;
  std::vector<float> log_p_;
  double log_far_ = 0.0;
};

}  // namespace locbench::baselines::global
