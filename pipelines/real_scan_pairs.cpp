#include "pipelines/real_scan_pairs.h"

#include <cmath>

#include "core/scan.h"
#include "core/units.h"

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

void apply_beam_angles(Log& log, const std::string& convention) {
  if (convention == "log") return;
  for (auto& r : log.laser) {
    if (r.scan.ranges.size() == 180) r.scan.bearings = even_bearings(180, -0.5 * kPi, 0.5 * kPi);
  }
}

}  // namespace locbench::experiments
