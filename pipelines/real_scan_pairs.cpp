#include "pipelines/real_scan_pairs.h"

#include <cmath>

#include "core/scan.h"
#include "core/trajectory.h"
#include "core/units.h"
#include "datasets/io/odometry_interpolation.h"

namespace locbench::experiments {

LineMap lines_as_map(const baselines::laser::ExtractionResult& lines) {
  LineMap m;
  m.name = "previous_scan";
  for (const baselines::laser::ExtractedLine& l : lines.lines) {
    const Segment s = l.fit.segment();
    if (s.length() > 1e-6) m.segments.push_back(s);
  }
  return m;
}

std::optional<std::size_t> scan_near(const std::map<double, std::size_t>& scans, double t) {
  auto it = scans.lower_bound(t - 1e-3);
  if (it == scans.end() || it->first > t + 1e-3) return std::nullopt;
  auto best = it;
  for (; it != scans.end() && it->first <= t + 1e-3; ++it) {
    if (std::abs(it->first - t) < std::abs(best->first - t)) best = it;
  }
  return best->second;
}

std::vector<RelationScanPair> relation_scan_pairs(const Log& log, double max_dt, std::size_t max_pairs) {
  const Trajectory odom = io::odometry_trajectory(log);
  std::map<double, std::size_t> scan_at;
  for (std::size_t i = 0; i < log.laser.size(); ++i) scan_at[log.laser[i].scan.timestamp] = i;
  std::vector<RelationScanPair> out;
  for (std::size_t k = 0; k < log.relations.size(); ++k) {
    if (max_pairs != 0 && out.size() >= max_pairs) break;
    const Relation& r = log.relations[k];
    if (r.t2 - r.t1 > max_dt) continue;
    const auto a = scan_near(scan_at, r.t1), b = scan_near(scan_at, r.t2);
    const auto o1 = odom.pose_at(r.t1), o2 = odom.pose_at(r.t2);
    if (!a || !b || !o1 || !o2) continue;
    out.push_back({k, *a, *b, between(*o1, *o2)});
  }
  return out;
}

void apply_beam_angles(Log& log, const std::string& convention) {
  if (convention == "log") return;
  for (auto& r : log.laser) {
    if (r.scan.ranges.size() == 180) r.scan.bearings = even_bearings(180, -0.5 * kPi, 0.5 * kPi);
  }
}

}  // namespace locbench::experiments
