#include "core/umbmark_measurements.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace locbench {

std::string to_string(UmbmarkDirection d) { return d == UmbmarkDirection::kClockwise ? "cw" : "ccw"; }

UmbmarkCentroids umbmark_centroids(const std::vector<UmbmarkReturn>& runs) {
  UmbmarkCentroids c;
  for (const auto& r : runs) {
    const Eigen::Vector2d e(r.x_error, r.y_error);
    if (r.direction == UmbmarkDirection::kClockwise) {
      c.cw += e;
      ++c.runs_cw;
    } else {
      c.ccw += e;
      ++c.runs_ccw;
    }
  }
  if (c.runs_cw > 0) c.cw /= c.runs_cw;
  if (c.runs_ccw > 0) c.ccw /= c.runs_ccw;
  c.e_max_syst = std::max(c.cw.norm(), c.ccw.norm());
  double scatter = 0.0;
  for (const auto& r : runs) {
    const Eigen::Vector2d& centroid = r.direction == UmbmarkDirection::kClockwise ? c.cw : c.ccw;
    scatter += (Eigen::Vector2d(r.x_error, r.y_error) - centroid).squaredNorm();
  }
  const int directions = (c.runs_cw > 0 ? 1 : 0) + (c.runs_ccw > 0 ? 1 : 0);
  const int dof = 2 * (c.runs_cw + c.runs_ccw - directions);
  c.run_sigma = dof > 0 ? std::sqrt(scatter / dof) : 0.0;
  return c;
}

namespace {

void require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument("UMBmark input: " + field + " " + rule);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void check_umbmark_input(const UmbmarkInput& in, bool need_leg_ticks) {
  require(positive(in.side_length), "side_length", "must be a finite length > 0");
  require(positive(in.nominal.diameter_left), "nominal.diameter_left", "must be > 0");
  require(positive(in.nominal.diameter_right), "nominal.diameter_right", "must be > 0");
  require(positive(in.nominal.wheelbase), "nominal.wheelbase", "must be > 0");
  require(positive(in.encoder.gear_ratio), "encoder.gear_ratio", "must be > 0");
  require(positive(in.encoder.counts_per_rev), "encoder.counts_per_rev", "must be > 0");
  require(positive(in.tape_measure_scale), "tape_measure_scale", "must be > 0");
  if (need_leg_ticks) {
    require(in.leg_ticks_left > 0, "leg_ticks_left", "must be > 0 (counts of one straight leg)");
    require(in.leg_ticks_right > 0, "leg_ticks_right", "must be > 0 (counts of one straight leg)");
  }
  int cw = 0, ccw = 0;
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    const auto& r = in.runs[i];
    require(std::isfinite(r.x_error) && std::isfinite(r.y_error), "runs[" + std::to_string(i) + "]",
            "has a non-finite return error");
    (r.direction == UmbmarkDirection::kClockwise ? cw : ccw) += 1;
  }
  require(cw > 0, "runs", "has no clockwise run (UMBmark needs both directions)");
  require(ccw > 0, "runs", "has no counter-clockwise run (UMBmark needs both directions)");
}

}  // namespace locbench
