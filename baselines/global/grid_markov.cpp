#include "baselines/global/grid_markov.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "baselines/global/options_fields.h"
#include "core/errors.h"
#include "core/units.h"

namespace locbench::baselines::global {

void validate(const GridMarkovOptions& o) { validate_fields(o, "GridMarkovOptions"); }

GridMarkov::GridMarkov(const LineMap& map, const GridMarkovOptions& options)
    : options_((validate(options), options)), field_(map, options.field) {
  const Bounds& b = field_.bounds();
  x0_ = b.min_x;
  y0_ = b.min_y;
  nx_ = std::max(1, static_cast<int>(std::ceil(b.width() / options_.cell_size)));
  ny_ = std::max(1, static_cast<int>(std::ceil(b.height() / options_.cell_size)));
  nt_ = std::max(1, static_cast<int>(std::lround(2.0 * kPi / options_.angular_cell)));
  const double cells = static_cast<double>(nx_) * ny_ * nt_;
  if (cells > options_.max_cells) {
    throw UsageError("GridMarkov: " + std::to_string(static_cast<long long>(cells)) +
                     " cells exceed max_cells; use larger cells");
  }
  init_global();
}

void GridMarkov::init_global() {
  belief_.assign(static_cast<std::size_t>(nx_) * ny_ * nt_, 0.0);
  std::fill(belief_.begin(), belief_.end(), 1.0 / static_cast<double>(belief_.size()));
  scratch_.assign(belief_.size(), 0.0);
  last_odometry_.reset();
}

void GridMarkov::init_pose(const Pose2& pose) {
  const auto clamp = [](int v, int n) { return std::min(std::max(v, 0), n - 1); };
  const int ix = clamp(static_cast<int>(std::floor((pose.x - x0_) / options_.cell_size)), nx_);
  const int iy = clamp(static_cast<int>(std::floor((pose.y - y0_) / options_.cell_size)), ny_);
  const int it = clamp(static_cast<int>(std::floor((pose.theta + kPi) / (2.0 * kPi / nt_))), nt_);
  std::fill(belief_.begin(), belief_.end(), 0.0);
  belief_[index(ix, iy, it)] = 1.0;
  last_odometry_.reset();
}

Pose2 GridMarkov::cell_pose(std::size_t i) const {
  const int ix = static_cast<int>(i % static_cast<std::size_t>(nx_));
  const int iy = static_cast<int>((i / static_cast<std::size_t>(nx_)) % static_cast<std::size_t>(ny_));
  const int it = static_cast<int>(i / (static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_)));
  const double dt = 2.0 * kPi / nt_;
  return {x0_ + (ix + 0.5) * options_.cell_size, y0_ + (iy + 0.5) * options_.cell_size, -kPi + (it + 0.5) * dt};
}

bool GridMarkov::update(const Pose2& odometry, const Scan& scan) {
  if (last_odometry_) {
    const OdometryDelta d = odometry_delta(*last_odometry_, odometry);
    if (moved_less_than(d, *last_odometry_, odometry, options_.update_min_distance, options_.update_min_angle)) {
      return false;
    }
    action_update(d);
  }
  last_odometry_ = odometry;
  perception_update(scan);
  ++updates_;
  return true;
}

void GridMarkov::action_update(const OdometryDelta& d) {
  std::fill(scratch_.begin(), scratch_.end(), 0.0);
  const double max_p = *std::max_element(belief_.begin(), belief_.end());
  const double threshold = options_.prune_threshold * max_p;
  const double dt = 2.0 * kPi / nt_;
  const double cs = options_.cell_size;
  for (int it = 0; it < nt_; ++it) {
    const double theta = -kPi + (it + 0.5) * dt;
    const double h = theta + d.rot1;
    const double mx = d.trans * std::cos(h) / cs, my = d.trans * std::sin(h) / cs;
    // Target heading in cell units, continuous; linear split between two slices.
    const double tt = (wrap_angle(h + d.rot2) + kPi) / dt - 0.5;
    const double ft = std::floor(tt);
    const double wt1 = tt - ft;
    const int t0 = ((static_cast<int>(ft) % nt_) + nt_) % nt_, t1 = (t0 + 1) % nt_;
    const double fx = std::floor(mx), fy = std::floor(my);
    const double wx1 = mx - fx, wy1 = my - fy;
    const int ox = static_cast<int>(fx), oy = static_cast<int>(fy);
    const double w[2][2][2] = {
        {{(1 - wx1) * (1 - wy1) * (1 - wt1), (1 - wx1) * (1 - wy1) * wt1},
         {(1 - wx1) * wy1 * (1 - wt1), (1 - wx1) * wy1 * wt1}},
        {{wx1 * (1 - wy1) * (1 - wt1), wx1 * (1 - wy1) * wt1}, {wx1 * wy1 * (1 - wt1), wx1 * wy1 * wt1}}};
    for (int iy = 0; iy < ny_; ++iy) {
      for (int ix = 0; ix < nx_; ++ix) {
        const double p = belief_[index(ix, iy, it)];
        if (p <= threshold || p == 0.0) continue;
        for (int a = 0; a < 2; ++a) {
          const int tx = ix + ox + a;
          if (tx < 0 || tx >= nx_) continue;  // mass leaving the map is lost
          for (int b = 0; b < 2; ++b) {
            const int ty = iy + oy + b;
            if (ty < 0 || ty >= ny_) continue;
            scratch_[index(tx, ty, t0)] += p * w[a][b][0];
            scratch_[index(tx, ty, t1)] += p * w[a][b][1];
          }
        }
      }
    }
  }
  belief_.swap(scratch_);
  const OdometryDelta s = delta_sigma(d, options_.motion);
  const double sxy = std::hypot(s.trans, d.trans * s.rot1) / cs;
  const double st = std::hypot(s.rot1, s.rot2) / dt;
  blur(sxy, st);
  normalise();
}

void GridMarkov::blur(double sxy, double st) {
  const auto kernel = [](double sigma) {
    std::vector<double> k;
    if (sigma < 0.2) return k;  // the splat's own spread is already larger
    const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
    double sum = 0.0;
    for (int i = -r; i <= r; ++i) {
      k.push_back(std::exp(-0.5 * i * i / (sigma * sigma)));
      sum += k.back();
    }
    for (double& v : k) v /= sum;
    return k;
  };
  const std::vector<double> kxy = kernel(sxy), kt = kernel(st);
  // axis 0: x, 1: y, 2: θ (wraps)
  const auto pass = [&](const std::vector<double>& k, int axis) {
    if (k.empty()) return;
    const int r = static_cast<int>(k.size() / 2);
    const int n = axis == 0 ? nx_ : axis == 1 ? ny_ : nt_;
    std::fill(scratch_.begin(), scratch_.end(), 0.0);
    for (int it = 0; it < nt_; ++it) {
      for (int iy = 0; iy < ny_; ++iy) {
        for (int ix = 0; ix < nx_; ++ix) {
          const double p = belief_[index(ix, iy, it)];
          if (p == 0.0) continue;
          const int c = axis == 0 ? ix : axis == 1 ? iy : it;
          for (int j = -r; j <= r; ++j) {
            int q = c + j;
            if (axis == 2) {
              q = ((q % n) + n) % n;
            } else if (q < 0 || q >= n) {
              continue;
            }
            const double v = p * k[static_cast<std::size_t>(j + r)];
            if (axis == 0)
              scratch_[index(q, iy, it)] += v;
            else if (axis == 1)
              scratch_[index(ix, q, it)] += v;
            else
              scratch_[index(ix, iy, q)] += v;
          }
        }
      }
    }
    belief_.swap(scratch_);
  };
  pass(kxy, 0);
  pass(kxy, 1);
  pass(kt, 2);
}

void GridMarkov::normalise() {
  double sum = 0.0;
  for (double p : belief_) sum += p;
  if (!(sum > 0.0)) {
    init_global();  // every cell's mass left the map: start over
    return;
  }
  for (double& p : belief_) p /= sum;
}

void GridMarkov::perception_update(const Scan& scan) {
  const std::vector<Eigen::Vector2d> ends = field_.beam_endpoints(scan);
  if (ends.empty()) return;
  const double dt = 2.0 * kPi / nt_;
  std::vector<double>& loglik = scratch_;  // free between updates
  std::vector<Eigen::Vector2d> rotated(ends.size());
  double max_log = -std::numeric_limits<double>::infinity();
  for (int it = 0; it < nt_; ++it) {
    const double theta = -kPi + (it + 0.5) * dt;
    const double c = std::cos(theta), s = std::sin(theta);
    for (std::size_t k = 0; k < ends.size(); ++k) {
      rotated[k] = {c * ends[k].x() - s * ends[k].y(), s * ends[k].x() + c * ends[k].y()};
    }
    for (int iy = 0; iy < ny_; ++iy) {
      const double y = y0_ + (iy + 0.5) * options_.cell_size;
      for (int ix = 0; ix < nx_; ++ix) {
        const double x = x0_ + (ix + 0.5) * options_.cell_size;
        double l = 0.0;
        for (const Eigen::Vector2d& e : rotated) l += field_.log_beam(x + e.x(), y + e.y());
        const std::size_t i = index(ix, iy, it);
        loglik[i] = l;
        max_log = std::max(max_log, l);
      }
    }
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < belief_.size(); ++i) {
    belief_[i] *= std::exp(loglik[i] - max_log);
    sum += belief_[i];
  }
  if (!(sum > 0.0)) {
    init_global();
    return;
  }
  const double u = options_.uniform_mix / static_cast<double>(belief_.size());
  for (double& p : belief_) p = (1.0 - options_.uniform_mix) * p / sum + u;
}

Pose2 GridMarkov::estimate() const {
  const std::size_t best = static_cast<std::size_t>(std::max_element(belief_.begin(), belief_.end()) - belief_.begin());
  const int bx = static_cast<int>(best % static_cast<std::size_t>(nx_));
  const int by = static_cast<int>((best / static_cast<std::size_t>(nx_)) % static_cast<std::size_t>(ny_));
  const int bt = static_cast<int>(best / (static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_)));
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0, sw = 0.0;
  for (int t = -1; t <= 1; ++t) {
    const int it = ((bt + t) % nt_ + nt_) % nt_;
    for (int y = -1; y <= 1; ++y) {
      for (int x = -1; x <= 1; ++x) {
        const int ix = bx + x, iy = by + y;
        if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) continue;
        const std::size_t i = index(ix, iy, it);
        const Pose2 p = cell_pose(i);
        const double w = belief_[i];
        sx += w * p.x;
        sy += w * p.y;
        sc += w * std::cos(p.theta);
        ss += w * std::sin(p.theta);
        sw += w;
      }
    }
  }
  return {sx / sw, sy / sw, std::atan2(ss, sc)};
}

double GridMarkov::mass_near(const Pose2& p, double radius, double angle) const {
  double m = 0.0;
  for (std::size_t i = 0; i < belief_.size(); ++i) {
    if (belief_[i] == 0.0) continue;
    const Pose2 c = cell_pose(i);
    if (std::hypot(c.x - p.x, c.y - p.y) <= radius && std::abs(angle_diff(c.theta, p.theta)) <= angle) {
      m += belief_[i];
    }
  }
  return m;
}

std::size_t GridMarkov::memory_bytes() const {
  return (belief_.capacity() + scratch_.capacity()) * sizeof(double) + field_.memory_bytes();
}

}  // namespace locbench::baselines::global
