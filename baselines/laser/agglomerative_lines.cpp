#include "baselines/laser/agglomerative_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "baselines/laser/extraction_steps.h"
#include "baselines/laser/options_fields.h"
#include "core/angle.h"
#include "core/chi_square.h"

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint;
namespace {

using detail::IndexRange;
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A line in model space: (α, r) in the sensor frame with its covariance.
struct ModelLine {
  double alpha = 0.0;
  double r = 0.0;
  double c_aa = kInf, c_ar = 0.0, c_rr = kInf;
};

// (α, r) and covariance of a least-squares line through `pts`, each with isotropic noise σ:
// var α = σ²/S_tt (S_tt the spread along the line), r = n(α)·c so
// δr = n·δc + (n'·c)δα with n' = dn/dα: var r = σ²/N + (n'·c)² var α, cov = (n'·c) var α.
ModelLine model_line(std::span<const Eigen::Vector2d> pts, double sigma, double floor_alpha, double floor_r) {
  const LineFit f = fit_line(pts);
  ModelLine m;
  m.alpha = f.line.beta;
  m.r = f.line.rho;
  const Eigen::Vector2d n_prime(-std::sin(m.alpha), std::cos(m.alpha));
  double s_tt = 0.0;
  for (const auto& p : pts) {
    const double t = n_prime.dot(p - f.centroid);
    s_tt += t * t;
  }
  const double var_alpha = s_tt > 0.0 ? sigma * sigma / s_tt : kInf;
  const double lever = n_prime.dot(f.centroid);
  m.c_aa = var_alpha + floor_alpha * floor_alpha;
  m.c_ar = std::isfinite(var_alpha) ? lever * var_alpha : 0.0;
  m.c_rr = sigma * sigma / static_cast<double>(pts.size()) + lever * lever * var_alpha + floor_r * floor_r;
  return m;
}

double mahalanobis2(const ModelLine& a, const ModelLine& b) {
  const double da = angle_diff(a.alpha, b.alpha), dr = a.r - b.r;
  const double s_aa = a.c_aa + b.c_aa, s_ar = a.c_ar + b.c_ar, s_rr = a.c_rr + b.c_rr;
  const double det = s_aa * s_rr - s_ar * s_ar;
  if (!(det > 0.0) || !std::isfinite(det)) return kInf;
  return (s_rr * da * da - 2.0 * s_ar * da * dr + s_aa * dr * dr) / det;
}

struct Cluster {
  ModelLine line;
  std::size_t head = kNone, tail = kNone;  // member points, linked through `next`
  std::size_t lo = 0, hi = 0;              // bounds of the union of the members' windows
  std::size_t nn = kNone;                  // cached nearest cluster and its d²
  double nn_d2 = kInf;
};

class Clustering {
 public:
  Clustering(std::span<const Eigen::Vector2d> s, const AgglomerativeOptions& o, std::size_t& work)
      : s_(s),
        o_(o),
        work_(work),
        next_(s.size(), kNone),
        win_lo_(s.size(), 0),
        win_hi_(s.size(), 0),
        stamp_(s.size(), 0) {}

  // Step 2 for point i with window [lo, hi): seeds a cluster if the window is a line.
  void seed(std::size_t i, std::size_t lo, std::size_t hi, double residual_limit) {
    const auto pts = s_.subspan(lo, hi - lo);
    const LineFit f = fit_line(pts);
    work_ += 2 * pts.size();
    const double sigma = o_.breakpoints.range_sigma;
    const double ss = f.rms * f.rms * static_cast<double>(pts.size());
    if (sigma > 0.0 ? ss / (sigma * sigma) > residual_limit : ss > 0.0) return;
    win_lo_[i] = lo;
    win_hi_[i] = hi;
    Cluster c;
    c.line = model_line(pts, sigma, o_.model_sigma_alpha, o_.model_sigma_r);
    c.head = c.tail = i;
    c.lo = lo;
    c.hi = hi;
    clusters_.push_back(c);
  }

  // Step 3: merge the closest pair until none is closer than `threshold` (d²).
  void run(double threshold) {
    active_.resize(clusters_.size());
    for (std::size_t k = 0; k < active_.size(); ++k) active_[k] = k;
    for (std::size_t a = 0; a < active_.size(); ++a) {
      for (std::size_t b = a + 1; b < active_.size(); ++b) offer(a, b, distance(a, b));
    }
    while (active_.size() > 1) {
      std::size_t best = kNone;
      for (const std::size_t k : active_) {
        if (best == kNone || clusters_[k].nn_d2 < clusters_[best].nn_d2) best = k;
      }
      if (!(clusters_[best].nn_d2 < threshold)) break;
      const std::size_t gone = clusters_[best].nn;
      absorb(best, gone);
      std::erase(active_, gone);
      update_after_merge(best, gone);
    }
  }

  // Cluster id of every point (kNone: seeded no cluster).
  std::vector<std::size_t> labels() const {
    std::vector<std::size_t> label(s_.size(), kNone);
    for (const std::size_t k : active_) {
      for (std::size_t m = clusters_[k].head; m != kNone; m = next_[m]) label[m] = k;
    }
    return label;
  }
  const ModelLine& line(std::size_t k) const { return clusters_[k].line; }

 private:
  double distance(std::size_t a, std::size_t b) {
    ++work_;
    return mahalanobis2(clusters_[a].line, clusters_[b].line);
  }
  // x becomes k's nearest neighbour if it is nearer than the one k has.
  void consider(std::size_t k, std::size_t x, double d2) {
    if (d2 < clusters_[k].nn_d2) clusters_[k].nn = x, clusters_[k].nn_d2 = d2;
  }
  void offer(std::size_t a, std::size_t b, double d2) {
    consider(a, b, d2);
    consider(b, a, d2);
  }
  void forget_nearest(std::size_t k) {
    clusters_[k].nn = kNone;
    clusters_[k].nn_d2 = kInf;
  }
  void rescan(std::size_t k) {
    forget_nearest(k);
    for (const std::size_t x : active_) {
      if (x != k) consider(k, x, distance(k, x));
    }
  }

  // Moves b's members into a and refits a to the points all their windows covered.
  void absorb(std::size_t a, std::size_t b) {
    Cluster& ca = clusters_[a];
    Cluster& cb = clusters_[b];
    next_[ca.tail] = cb.head;
    ca.tail = cb.tail;
    ca.lo = std::min(ca.lo, cb.lo);
    ca.hi = std::max(ca.hi, cb.hi);
    ++generation_;
    for (std::size_t m = ca.head; m != kNone; m = next_[m]) {
      for (std::size_t i = win_lo_[m]; i < win_hi_[m]; ++i) stamp_[i] = generation_;
      work_ += win_hi_[m] - win_lo_[m];
    }
    scratch_.clear();
    for (std::size_t i = ca.lo; i < ca.hi; ++i) {
      if (stamp_[i] == generation_) scratch_.push_back(s_[i]);
    }
    work_ += 2 * (ca.hi - ca.lo);
    ca.line = model_line(scratch_, o_.breakpoints.range_sigma, o_.model_sigma_alpha, o_.model_sigma_r);
  }

  // Only distances to the merged cluster `a` changed; `gone` no longer exists.
  void update_after_merge(std::size_t a, std::size_t gone) {
    forget_nearest(a);
    for (const std::size_t k : active_) {
      if (k == a) continue;
      const double d2 = distance(k, a);
      consider(a, k, d2);
      Cluster& ck = clusters_[k];
      if (ck.nn == a || ck.nn == gone) {
        if (d2 <= ck.nn_d2) {
          ck.nn = a, ck.nn_d2 = d2;  // still the minimum: no other distance of k changed
        } else {
          rescan(k);
        }
      } else {
        consider(k, a, d2);
      }
    }
  }

  std::span<const Eigen::Vector2d> s_;
  const AgglomerativeOptions& o_;
  std::size_t& work_;
  std::vector<std::size_t> next_, win_lo_, win_hi_;
  std::vector<unsigned> stamp_;
  unsigned generation_ = 0;
  std::vector<Cluster> clusters_;
  std::vector<std::size_t> active_;
  std::vector<Eigen::Vector2d> scratch_;
};

}  // namespace

void validate(const AgglomerativeOptions& o) {
  validate_fields(o, "AgglomerativeOptions");
  detail::require(o.breakpoints.range_sigma > 0.0 || o.model_sigma_alpha > 0.0,
                  "AgglomerativeOptions: breakpoints.range_sigma or model_sigma_alpha must be > 0");
}

ExtractionResult agglomerative_lines(std::span<const ScanPoint> points, LineFrame frame,
                                     const AgglomerativeOptions& options) {
  validate(options);
  ExtractionResult result;
  const std::size_t n = points.size();
  const std::vector<Eigen::Vector2d> s = detail::sensor_points(points);
  // 1. filter
  const std::vector<IndexRange> runs = detail::breakpoint_runs(points, options.breakpoints);
  const std::vector<std::size_t> run_of = detail::run_index(runs, n);
  result.work += n;
  const std::size_t min_run = std::max<std::size_t>(options.acceptance.min_points, 3);

  // 2. local lines
  Clustering clustering(s, options, result.work);
  const auto window = static_cast<std::size_t>(options.window);
  for (const IndexRange& run : runs) {
    if (run.size() < min_run) continue;
    const std::size_t w = std::min(window, run.size());
    const double limit = chi_square_quantile(ChiSquareDof(static_cast<double>(w - 2)), options.window_confidence);
    for (std::size_t i = run.begin; i < run.end; ++i) {
      const std::size_t lo = std::clamp(i, run.begin + w / 2, run.end - (w - w / 2)) - w / 2;
      clustering.seed(i, lo, lo + w, limit);
    }
  }
  // 3. clustering
  clustering.run(chi_square_quantile(ChiSquareDof(2.0), options.merge_confidence));
  std::vector<std::size_t> label = clustering.labels();

  // 4. left-out points join an adjacent point's cluster (labels as clustering left them)
  std::vector<std::size_t> prev(n, kNone), next(n, kNone);
  for (std::size_t i = 1; i < n; ++i) {
    if (run_of[i] != run_of[i - 1]) continue;
    prev[i] = label[i - 1] != kNone ? label[i - 1] : prev[i - 1];
  }
  for (std::size_t i = n; i-- > 1;) {
    if (run_of[i] != run_of[i - 1]) continue;
    next[i - 1] = label[i] != kNone ? label[i] : next[i];
  }
  const std::vector<std::size_t> seeded = label;
  for (std::size_t i = 0; i < n; ++i) {
    if (seeded[i] != kNone || runs[run_of[i]].size() < min_run) continue;
    double best = options.assign_distance;
    for (const std::size_t k : {prev[i], next[i]}) {
      if (k == kNone) continue;
      ++result.work;
      const ModelLine& m = clustering.line(k);
      const double d = detail::LineNormal({m.r, m.alpha}).distance(s[i]);
      if (d <= best) best = d, label[i] = k;
    }
  }

  // pieces of every cluster, contiguous in the scan, fitted and accepted
  std::vector<std::pair<std::size_t, std::size_t>> by_label;  // (cluster, point)
  for (std::size_t i = 0; i < n; ++i) {
    if (label[i] != kNone) by_label.emplace_back(label[i], i);
  }
  std::sort(by_label.begin(), by_label.end());
  std::vector<std::size_t> members;
  std::vector<Eigen::Vector2d> scratch;
  const auto gap = static_cast<std::size_t>(options.max_gap_points);
  for (std::size_t g = 0; g < by_label.size();) {
    std::size_t h = g;
    members.clear();
    while (h < by_label.size() && by_label[h].first == by_label[g].first) {
      members.push_back(by_label[h++].second);
    }
    for (const IndexRange& piece : detail::contiguous_pieces(members, run_of, gap)) {
      detail::append_if_accepted(points, std::span<const std::size_t>(members).subspan(piece.begin, piece.size()), s,
                                 frame, options.acceptance, scratch, result.lines);
    }
    g = h;
  }
  detail::sort_by_first_beam(result.lines);
  return result;
}

}  // namespace locbench::baselines::laser
