#include "baselines/laser/rwht.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "baselines/laser/extraction_steps.h"
#include "baselines/laser/options_fields.h"
#include "core/angle.h"

namespace locbench::baselines::laser {
using locbench::laser::fit_line, locbench::laser::LineFit, locbench::laser::ScanPoint;
namespace {

using detail::IndexRange;
constexpr double kMaxCells = 2e7;  // 240 MB of accumulator: a bin size error, not a setting
// Grids up to this many cells (48 MB; the default 1° × 5 cm grid of an 80 m scan has 0.58 M) stay
// allocated per thread from scan to scan.
constexpr std::size_t kRetainedCells = 4'000'000;

// The scan's beam spacing: the median bearing step between consecutive points (robust to
// missing beams).
double beam_spacing(std::span<const ScanPoint> points) {
  std::vector<double> steps;
  steps.reserve(points.size());
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double d = std::abs(points[i].bearing - points[i - 1].bearing);
    if (d > 0.0) steps.push_back(d);
  }
  if (steps.empty()) return 1.0;
  const auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), mid, steps.end());
  return *mid;
}

// The vote and voter counts of every cell, kept by each thread from scan to scan: an
// accumulator zeroes the cells it touched when it is done, so a scan pays for its own votes and
// not for clearing the whole (α, r) grid.
struct CellStore {
  std::vector<double> votes;
  std::vector<std::uint32_t> voters;
  std::vector<std::size_t> touched;  // the cells with a voter, in voting order
};

struct Accumulator {
  std::size_t n_alpha = 0, n_r = 0;
  double d_alpha = 0.0, d_r = 0.0;
  std::vector<double> cos_a, sin_a;
  CellStore& store;
  std::span<double> votes;
  std::span<std::uint32_t> voters;

  Accumulator(double angle_bin, double range_bin, double r_max, CellStore& cells) : d_r(range_bin), store(cells) {
    n_alpha = static_cast<std::size_t>(std::ceil(2.0 * kPi / angle_bin - 1e-9));
    d_alpha = 2.0 * kPi / static_cast<double>(n_alpha);
    n_r = static_cast<std::size_t>(std::floor(r_max / range_bin)) + 1;
    cos_a.resize(n_alpha);
    sin_a.resize(n_alpha);
    for (std::size_t k = 0; k < n_alpha; ++k) {
      cos_a[k] = std::cos(alpha(k));
      sin_a[k] = std::sin(alpha(k));
    }
    const std::size_t n = n_alpha * n_r;
    if (store.votes.size() < n) {
      store.votes.resize(n, 0.0);
      store.voters.resize(n, 0);
    }
    votes = std::span<double>(store.votes).first(n);
    voters = std::span<std::uint32_t>(store.voters).first(n);
  }
  ~Accumulator() {
    if (store.votes.size() > kRetainedCells) {  // a fine grid is not kept for the next scan
      store = CellStore{};
      return;
    }
    for (const std::size_t c : store.touched) {
      votes[c] = 0.0;
      voters[c] = 0;
    }
    store.touched.clear();
  }
  Accumulator(const Accumulator&) = delete;
  Accumulator& operator=(const Accumulator&) = delete;
  const std::vector<std::size_t>& touched() const { return store.touched; }
  double alpha(std::size_t k) const { return -kPi + (static_cast<double>(k) + 0.5) * d_alpha; }
  double r(std::size_t j) const { return (static_cast<double>(j) + 0.5) * d_r; }
  // A cell's rank, which orders ties (α-major), and its slot in the store (r-major: a point's
  // votes at neighbouring α mostly fall in neighbouring slots).
  std::size_t cell(std::size_t k, std::size_t j) const { return k * n_r + j; }
  std::size_t slot(std::size_t k, std::size_t j) const { return j * n_alpha + k; }

  void vote(const Eigen::Vector2d& p, double weight) {
    for (std::size_t k = 0; k < n_alpha; ++k) {
      const double rr = p.x() * cos_a[k] + p.y() * sin_a[k];
      if (rr < 0.0) continue;
      const auto j = static_cast<std::size_t>(rr / d_r);
      if (j >= n_r) continue;
      const std::size_t c = slot(k, j);
      if (voters[c] == 0) store.touched.push_back(c);  // first: a failed push leaves the cell clean
      ++voters[c];
      votes[c] += weight;
    }
  }

  // Whether (k, j) beats every other cell within `radius` bins (α wraps; ties go to the lower
  // cell index so a plateau yields one peak).
  bool is_peak(std::size_t k, std::size_t j, int radius) const {
    const double v = votes[slot(k, j)];
    const auto na = static_cast<long>(n_alpha);
    for (int dk = -radius; dk <= radius; ++dk) {
      const auto kk = static_cast<std::size_t>(((static_cast<long>(k) + dk) % na + na) % na);
      for (int dj = -radius; dj <= radius; ++dj) {
        const long jl = static_cast<long>(j) + dj;
        if (jl < 0 || jl >= static_cast<long>(n_r)) continue;
        const auto jj = static_cast<std::size_t>(jl);
        if (kk == k && jj == j) continue;
        const double u = votes[slot(kk, jj)];
        if (u > v || (u == v && cell(kk, jj) < cell(k, j))) return false;
      }
    }
    return true;
  }
};

struct Candidate {
  double votes;
  std::size_t k, j;
};

constexpr std::size_t kFree = static_cast<std::size_t>(-1);

// The scan as the phases see it: sensor-frame points and the breakpoint run of each.
struct ScanView {
  std::span<const ScanPoint> points;
  std::vector<Eigen::Vector2d> s;
  std::vector<std::size_t> run_of;
  std::size_t n = 0;
  std::size_t gap = 0;  // max_gap_points
};

// Peaks with non-maximum suppression, strongest first.
std::vector<Candidate> peak_candidates(const Accumulator& acc, const RwhtOptions& options) {
  std::vector<Candidate> candidates;
  for (const std::size_t c : acc.touched()) {  // a cell without votes is never a peak
    if (acc.votes[c] <= 0.0) continue;
    const std::size_t k = c % acc.n_alpha, j = c / acc.n_alpha;
    // thresholds on the cell with its two range neighbours: a short line whose votes
    // straddle a range-bin boundary still counts all of them
    double votes = 0.0;
    std::size_t voters = 0;
    for (std::size_t jj = j > 0 ? j - 1 : 0; jj <= j + 1 && jj < acc.n_r; ++jj) {
      votes += acc.votes[acc.slot(k, jj)];
      voters += acc.voters[acc.slot(k, jj)];
    }
    if (votes < options.min_peak_votes || voters < options.acceptance.min_points) continue;
    if (acc.is_peak(k, j, options.nms_radius)) candidates.push_back({acc.votes[c], k, j});
  }
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    return a.votes != b.votes ? a.votes > b.votes : acc.cell(a.k, a.j) < acc.cell(b.k, b.j);
  });
  return candidates;
}

LineParams fit_points(const std::vector<std::size_t>& members, const ScanView& v) {
  std::vector<Eigen::Vector2d> scratch;
  for (const std::size_t i : members) scratch.push_back(v.s[i]);
  return fit_line(scratch).line;
}

// The points within the peak cell's band (half a range bin, the cell's angular width at the
// point's range and 3σ of range noise), cut to its largest contiguous stretch: the band also
// catches stray points of other walls crossing it.
std::vector<std::size_t> band_stretch(const ScanView& v, const Accumulator& acc, const RwhtPeak& peak,
                                      const RwhtOptions& options) {
  const double half_sin = std::sin(0.5 * acc.d_alpha);
  std::vector<std::size_t> members;
  const detail::LineNormal cell(peak.cell);
  for (std::size_t i = 0; i < v.n; ++i) {
    const double band = 0.5 * acc.d_r + v.points[i].range * half_sin + 3.0 * options.breakpoints.range_sigma;
    if (cell.distance(v.s[i]) <= band) {
      members.push_back(i);
    }
  }
  if (members.size() < options.acceptance.min_points) return members;
  const std::vector<IndexRange> pieces = detail::contiguous_pieces(members, v.run_of, v.gap);
  const IndexRange largest = *std::max_element(
      pieces.begin(), pieces.end(), [](const IndexRange& a, const IndexRange& b) { return a.size() < b.size(); });
  members.erase(members.begin() + static_cast<std::ptrdiff_t>(largest.end), members.end());
  members.erase(members.begin(), members.begin() + static_cast<std::ptrdiff_t>(largest.begin));
  return members;
}

// The stretch trimmed until all its points are within inlier_distance: of the first, the last
// and the farthest point, drop the one whose removal leaves the smallest largest residual (a
// stray point at an end of the stretch has the leverage to pull the fit onto itself and need
// not be the farthest).
std::vector<std::size_t> trim_to_inliers(std::vector<std::size_t> members, const ScanView& v,
                                         const RwhtOptions& options, std::size_t& work) {
  std::vector<Eigen::Vector2d> scratch;
  while (members.size() >= options.acceptance.min_points) {
    const auto worst_residual = [&](std::size_t skip, std::size_t& at) {
      scratch.clear();
      for (std::size_t m = 0; m < members.size(); ++m) {
        if (m != skip) scratch.push_back(v.s[members[m]]);
      }
      const detail::LineNormal l(fit_line(scratch).line);
      double worst = -1.0;
      for (std::size_t m = 0; m < members.size(); ++m) {
        const double d = m == skip ? -1.0 : l.distance(v.s[members[m]]);
        if (d > worst) worst = d, at = m;
      }
      work += 2 * members.size();
      return worst;
    };
    std::size_t farthest = 0, ignored = 0;
    if (worst_residual(members.size(), farthest) <= options.inlier_distance) break;
    std::size_t drop = farthest;
    double best = worst_residual(farthest, ignored);
    for (const std::size_t end_point : {std::size_t{0}, members.size() - 1}) {
      const double r = worst_residual(end_point, ignored);
      if (r < best) best = r, drop = end_point;
    }
    members.erase(members.begin() + static_cast<std::ptrdiff_t>(drop));
  }
  return members;
}

// Refit and take every point of the scan within inlier_distance, up to three rounds or until the
// inliers stay the same.
std::vector<std::size_t> refit_inliers(std::vector<std::size_t> members, const ScanView& v, const RwhtOptions& options,
                                       std::size_t& work) {
  std::vector<std::size_t> previous;
  for (int round = 0; round < 3; ++round) {
    const detail::LineNormal fitted(fit_points(members, v));
    previous.swap(members);
    members.clear();
    for (std::size_t i = 0; i < v.n; ++i) {
      if (fitted.distance(v.s[i]) <= options.inlier_distance) members.push_back(i);
    }
    work += v.n;
    if (members == previous || members.size() < options.acceptance.min_points) break;
  }
  return members;
}

// Which line holds each point, each line's sensor-frame fit and the peak it came from. A point
// belongs to one line; a later line may take the end point of an earlier one's stretch when it
// lies nearer to it (the stronger line would otherwise keep the first beam past a corner).
struct Claims {
  std::vector<std::size_t> owner;
  std::vector<LineParams> line_of;
  std::vector<std::size_t> peak_of;
};

// Whether point i ends its line's stretch of the scan (only such points can change lines).
bool at_end(const Claims& c, std::size_t i) {
  const std::size_t n = c.owner.size();
  return i == 0 || i + 1 == n || c.owner[i - 1] != c.owner[i] || c.owner[i + 1] != c.owner[i];
}

// The new line's members without the held points it may not take: a held end point moves when
// it is nearer to this line than to its holder's, both lines fitted without it (a point must not
// pull the line it is judged against towards itself).
std::vector<std::size_t> contest_held_points(std::vector<std::size_t> members, const LineParams& line,
                                             const Claims& claims, const ScanView& v, std::size_t& work) {
  LineParams own = line;
  std::vector<std::size_t> free_members;
  for (const std::size_t i : members) {
    if (claims.owner[i] == kFree) free_members.push_back(i);
  }
  if (free_members.size() >= 2 && free_members.size() < members.size()) own = fit_points(free_members, v);
  std::vector<Eigen::Vector2d> scratch;
  std::erase_if(members, [&](std::size_t i) {
    if (claims.owner[i] == kFree) return false;
    if (!at_end(claims, i)) return true;
    scratch.clear();  // the holder's line without i, for the same reason
    for (std::size_t j = 0; j < v.n; ++j) {
      if (claims.owner[j] == claims.owner[i] && j != i) scratch.push_back(v.s[j]);
    }
    work += v.n;
    const LineParams holder = scratch.size() >= 2 ? fit_line(scratch).line : claims.line_of[claims.owner[i]];
    return !(detail::LineNormal(own).distance(v.s[i]) < detail::LineNormal(holder).distance(v.s[i]));
  });
  return members;
}

// The points of one peak: band, trim, refit, inliers, then contiguous pieces claimed as lines
// when accepted. Returns whether the peak produced a line.
bool claim_peak(const Candidate& c, std::size_t peak_index, const Accumulator& acc, const ScanView& v,
                const RwhtOptions& options, Claims& claims, std::size_t& work) {
  const RwhtPeak peak{{acc.r(c.j), acc.alpha(c.k)}, c.votes};
  std::vector<std::size_t> members = band_stretch(v, acc, peak, options);
  work += v.n;
  if (members.size() < options.acceptance.min_points) return false;
  members = trim_to_inliers(std::move(members), v, options, work);
  if (members.size() < options.acceptance.min_points) return false;
  members = refit_inliers(std::move(members), v, options, work);
  if (members.size() < options.acceptance.min_points) return false;
  // A second peak of a line already found (its butterfly spreads over neighbouring cells).
  const LineParams line = fit_points(members, v);
  if (std::any_of(claims.line_of.begin(), claims.line_of.end(), [&](const LineParams& l) {
        return std::abs(angle_diff(l.beta, line.beta)) < acc.d_alpha && std::abs(l.rho - line.rho) < acc.d_r;
      })) {
    return false;
  }
  const std::vector<std::size_t> all = contest_held_points(std::move(members), line, claims, v, work);
  std::vector<Eigen::Vector2d> scratch;
  bool produced = false;
  for (const IndexRange& piece : detail::contiguous_pieces(all, v.run_of, v.gap)) {
    const auto idx = std::span<const std::size_t>(all).subspan(piece.begin, piece.size());
    const std::optional<LineFit> fit = detail::accepted_fit(idx, v.s, options.acceptance, scratch);
    if (!fit) continue;
    for (const std::size_t i : idx) claims.owner[i] = claims.line_of.size();
    claims.line_of.push_back(fit->line);
    claims.peak_of.push_back(peak_index);
    produced = true;
  }
  return produced;
}

std::vector<std::vector<std::size_t>> points_by_line(const std::vector<std::size_t>& owner, std::size_t lines) {
  std::vector<std::vector<std::size_t>> held(lines);
  for (std::size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] != kFree) held[owner[i]].push_back(i);
  }
  return held;
}

// The owners as the lines finally stand: a line that lost points is cut and checked again, and
// points left without a line join the line of a neighbour in the scan within inlier_distance
// (the last step of the agglomerative extractor too).
std::vector<std::size_t> settled_owners(const Claims& claims, const ScanView& v, const RwhtOptions& options,
                                        std::size_t& work) {
  const std::vector<std::vector<std::size_t>> held = points_by_line(claims.owner, claims.line_of.size());
  std::vector<std::size_t> owner(v.n, kFree);
  std::vector<Eigen::Vector2d> scratch;
  for (std::size_t l = 0; l < held.size(); ++l) {
    for (const IndexRange& piece : detail::contiguous_pieces(held[l], v.run_of, v.gap)) {
      const auto idx = std::span<const std::size_t>(held[l]).subspan(piece.begin, piece.size());
      if (!detail::accepted_fit(idx, v.s, options.acceptance, scratch)) continue;
      for (const std::size_t i : idx) owner[i] = l;
    }
  }
  const std::vector<std::size_t> settled = owner;
  for (std::size_t i = 0; i < v.n; ++i) {
    if (settled[i] != kFree) continue;
    double best = options.inlier_distance;
    for (const std::size_t j : {i - 1, i + 1}) {  // i − 1 wraps to a huge index at i = 0
      if (j >= v.n || settled[j] == kFree || v.run_of[j] != v.run_of[i]) continue;
      ++work;
      const double d = detail::LineNormal(claims.line_of[settled[j]]).distance(v.s[i]);
      if (d <= best) best = d, owner[i] = settled[j];
    }
  }
  return owner;
}

// The accepted pieces of each line in order of their first beam, with the peak of each.
void append_lines_in_beam_order(const std::vector<std::size_t>& owner, const Claims& claims, const ScanView& v,
                                LineFrame frame, const RwhtOptions& options, RwhtExtraction& out) {
  const std::vector<std::vector<std::size_t>> held = points_by_line(owner, claims.line_of.size());
  std::vector<Eigen::Vector2d> scratch;
  std::vector<std::pair<std::size_t, std::size_t>> order;  // (first beam, line)
  std::vector<ExtractedLine> lines;
  std::vector<std::size_t> line_peak;
  for (std::size_t l = 0; l < held.size(); ++l) {
    for (const IndexRange& piece : detail::contiguous_pieces(held[l], v.run_of, v.gap)) {
      const auto idx = std::span<const std::size_t>(held[l]).subspan(piece.begin, piece.size());
      if (detail::append_if_accepted(v.points, idx, v.s, frame, options.acceptance, scratch, lines)) {
        line_peak.push_back(claims.peak_of[l]);
        order.emplace_back(lines.back().points.front().beam, lines.size() - 1);
      }
    }
  }
  std::sort(order.begin(), order.end());
  for (const auto& [beam, l] : order) {
    out.extraction.lines.push_back(std::move(lines[l]));
    out.line_peak.push_back(line_peak[l]);
  }
}

}  // namespace

void validate(const RwhtOptions& o) { validate_fields(o, "RwhtOptions"); }

RwhtExtraction rwht_lines(std::span<const ScanPoint> points, LineFrame frame, const RwhtOptions& options) {
  validate(options);
  RwhtExtraction out;
  std::size_t& work = out.extraction.work;
  const std::size_t n = points.size();
  if (n < options.acceptance.min_points || n < 2) return out;
  ScanView v{points, detail::sensor_points(points), {}, n, static_cast<std::size_t>(options.max_gap_points)};
  v.run_of = detail::run_index(detail::breakpoint_runs(points, options.breakpoints), n);
  work += n;

  // 1. vote
  double r_max = 0.0;
  for (const ScanPoint& p : points) r_max = std::max(r_max, p.range);
  const double n_cells = std::ceil(2.0 * kPi / options.angle_bin) * (std::floor(r_max / options.range_bin) + 1.0);
  detail::require(n_cells <= kMaxCells, "RwhtOptions: angle_bin and range_bin give " + std::to_string(n_cells) +
                                            " cells (max " + std::to_string(kMaxCells) + ")");
  thread_local CellStore cells;
  Accumulator acc(options.angle_bin, options.range_bin, r_max, cells);
  out.cells = acc.n_alpha * acc.n_r;
  const double dphi = beam_spacing(points);
  for (std::size_t i = 0; i < n; ++i) acc.vote(v.s[i], points[i].range * dphi);
  work += n * acc.n_alpha;

  // 2. peaks with non-maximum suppression, strongest first
  const std::vector<Candidate> candidates = peak_candidates(acc, options);
  work += out.cells;

  // 3. the points of each peak, claimed as lines
  Claims claims{std::vector<std::size_t>(n, kFree), {}, {}};
  for (const Candidate& c : candidates) {
    if (claim_peak(c, out.peaks.size(), acc, v, options, claims, work)) {
      out.peaks.push_back({{acc.r(c.j), acc.alpha(c.k)}, c.votes});
    }
  }

  // 4. the lines as their points finally stand
  append_lines_in_beam_order(settled_owners(claims, v, options, work), claims, v, frame, options, out);
  return out;
}

}  // namespace locbench::baselines::laser
