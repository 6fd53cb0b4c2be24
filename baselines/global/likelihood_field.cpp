#include "baselines/global/likelihood_field.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "baselines/global/options_fields.h"
#include "core/errors.h"
#include "core/input_limits.h"
#include "core/units.h"

namespace locbench::baselines::global {

void validate(const LikelihoodFieldOptions& o) {
  validate_fields(o, "LikelihoodFieldOptions");
  if (!(o.z_hit + o.z_random > 0.0)) {
    throw UsageError("LikelihoodFieldOptions: z_hit and z_random must not both be 0");
  }
}

Bounds map_bounds(const LineMap& map) {
  if (map.segments.empty()) throw UsageError("likelihood field: the map has no segments");
  Bounds b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Segment& s : map.segments) {
    for (const Eigen::Vector2d& p : {s.p1, s.p2}) {
      b.min_x = std::min(b.min_x, p.x());
      b.min_y = std::min(b.min_y, p.y());
      b.max_x = std::max(b.max_x, p.x());
      b.max_y = std::max(b.max_y, p.y());
    }
  }
  return b;
}

LikelihoodField::LikelihoodField(const LineMap& map, const LikelihoodFieldOptions& options) : options_(options) {
  validate(options_);
  map_bounds_ = map_bounds(map);
  const double res = options_.resolution;
  origin_x_ = map_bounds_.min_x - options_.margin;
  origin_y_ = map_bounds_.min_y - options_.margin;
  inv_res_ = 1.0 / res;
  nx_ = static_cast<int>(std::ceil((map_bounds_.width() + 2.0 * options_.margin) / res)) + 1;
  ny_ = static_cast<int>(std::ceil((map_bounds_.height() + 2.0 * options_.margin) / res)) + 1;
  if (const double cells = static_cast<double>(nx_) * ny_; !(cells <= limits::kLikelihoodFieldCells.max)) {
    throw UsageError(
        fmt::format("likelihood field: {:.6g} cells exceed the limit {} (field.resolution {} m, "
                    "field.margin {} m; see `locbench --help`, \"Input limits\"): use a coarser resolution",
                    cells, limits::limit_text(limits::kLikelihoodFieldCells.max), res, options_.margin));
  }
  const std::size_t n = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  // Nearest-segment transform: seed the cells the segments pass through, then propagate the
  // nearest segment's index in a forward and a backward raster pass (8 neighbours), keeping the
  // exact distance from each cell centre to its candidate segments.
  std::vector<int> nearest(n, -1);
  std::vector<float> dist(n, std::numeric_limits<float>::infinity());
  const auto centre = [&](int cx, int cy) {
    return Eigen::Vector2d(origin_x_ + (cx + 0.5) * res, origin_y_ + (cy + 0.5) * res);
  };
  const auto consider = [&](std::size_t cell, int cx, int cy, int seg) {
    const float d =
        static_cast<float>(distance_to_segment(map.segments[static_cast<std::size_t>(seg)], centre(cx, cy)));
    if (d < dist[cell]) {
      dist[cell] = d;
      nearest[cell] = seg;
    }
  };
  for (std::size_t s = 0; s < map.segments.size(); ++s) {
    const Segment& seg = map.segments[s];
    const int steps = std::max(1, static_cast<int>(std::ceil(seg.length() / (0.5 * res))));
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = seg.p1 + (seg.p2 - seg.p1) * (static_cast<double>(k) / steps);
      const int cx = static_cast<int>(std::floor((p.x() - origin_x_) * inv_res_));
      const int cy = static_cast<int>(std::floor((p.y() - origin_y_) * inv_res_));
      if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) continue;
      consider(static_cast<std::size_t>(cy) * nx_ + cx, cx, cy, static_cast<int>(s));
    }
  }
  const auto pass = [&](int dir) {
    const int y0 = dir > 0 ? 0 : ny_ - 1, y1 = dir > 0 ? ny_ : -1;
    const int x0 = dir > 0 ? 0 : nx_ - 1, x1 = dir > 0 ? nx_ : -1;
    const int nb[4][2] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    for (int cy = y0; cy != y1; cy += dir) {
      for (int cx = x0; cx != x1; cx += dir) {
        const std::size_t cell = static_cast<std::size_t>(cy) * nx_ + cx;
        for (const auto& o : nb) {
          const int qx = cx + dir * o[0], qy = cy + dir * o[1];
          if (qx < 0 || qy < 0 || qx >= nx_ || qy >= ny_) continue;
          const int seg = nearest[static_cast<std::size_t>(qy) * nx_ + qx];
          if (seg >= 0 && seg != nearest[cell]) consider(cell, cx, cy, seg);
        }
      }
    }
  };
  pass(+1);
  pass(-1);
  pass(+1);
  const double s = options_.sigma_hit;
  const double norm = options_.z_hit / (s * std::sqrt(2.0 * kPi));
  const double random = options_.z_random / options_.z_max;
  const auto log_p = [&](double d) {
    d = std::min(d, options_.max_distance);
    return std::log(norm * std::exp(-0.5 * d * d / (s * s)) + random);
  };
  distance_.resize(n);
  log_p_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::min(static_cast<double>(dist[i]), options_.max_distance);
    distance_[i] = static_cast<float>(d);
    log_p_[i] = static_cast<float>(log_p(d));
  }
  log_far_ = log_p(options_.max_distance);
}

double LikelihoodField::distance(double x, double y) const {
  const int cx = static_cast<int>(std::floor((x - origin_x_) * inv_res_));
  const int cy = static_cast<int>(std::floor((y - origin_y_) * inv_res_));
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return options_.max_distance;
  return distance_[static_cast<std::size_t>(cy) * nx_ + cx];
}

std::vector<Eigen::Vector2d> LikelihoodField::beam_endpoints(const Scan& scan) const {
  std::vector<std::size_t> valid;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (scan.valid(i) && scan.ranges[i] < options_.z_max) valid.push_back(i);
  }
  std::vector<Eigen::Vector2d> out;
  const std::size_t k = std::min<std::size_t>(valid.size(), static_cast<std::size_t>(options_.beams));
  for (std::size_t j = 0; j < k; ++j) {
    // Evenly spread: the j-th of k picks among the valid beams.
    const std::size_t i = valid[k == 1 ? valid.size() / 2 : j * (valid.size() - 1) / (k - 1)];
    out.push_back(scan.sensor_pose * scan.point(i));
  }
  return out;
}

double LikelihoodField::log_likelihood(const Pose2& robot, const std::vector<Eigen::Vector2d>& endpoints) const {
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  double sum = 0.0;
  for (const Eigen::Vector2d& p : endpoints) {
    sum += log_beam(robot.x + c * p.x() - s * p.y(), robot.y + s * p.x() + c * p.y());
  }
  return sum;
}

}  // namespace locbench::baselines::global
