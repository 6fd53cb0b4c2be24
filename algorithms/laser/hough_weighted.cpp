#include "algorithms/laser/hough_weighted.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/json_options.h"

namespace locbench::laser {

const char* to_string(HoughWeighting w) {
  switch (w) {
    case HoughWeighting::kCount: return "count";
    case HoughWeighting::kRange: return "range";
    case HoughWeighting::kRangeIncidence: return "range_incidence";
  }
  return "?";
}

HoughWeighting hough_weighting_from_string(const std::string& s) {
  if (s == "count") return HoughWeighting::kCount;
  if (s == "range") return HoughWeighting::kRange;
  if (s == "range_incidence") return HoughWeighting::kRangeIncidence;
  throw UsageError("weighting must be \"count\", \"range\" or \"range_incidence\", got \"" + s +
                   "\"");
}

void validate(const HoughWeight& g) {
  if (!(std::isfinite(g.rho_min) && g.rho_min > 0.0)) {
    throw UsageError("HoughWeight.rho_min must be finite and > 0");
  }
  if (!(g.min_cos_incidence > 0.0 && g.min_cos_incidence <= 1.0)) {
    throw UsageError("HoughWeight.min_cos_incidence must be in (0, 1]");
  }
}

void validate(const HoughOptions& o) {
  if (!(std::isfinite(o.d_limit) && o.d_limit > 0.0)) {
    throw UsageError("HoughOptions.d_limit must be finite and > 0");
  }
  validate(o.g);
}

void to_json(nlohmann::json& j, const HoughWeight& g) {
  j = {{"kind", to_string(g.kind)},
       {"rho_min", g.rho_min},
       {"min_cos_incidence", g.min_cos_incidence}};
}

void from_json(const nlohmann::json& j, HoughWeight& g) {
  StrictJsonReader r(j, "HoughWeight");
  std::string kind = to_string(g.kind);
  r.read("kind", kind);
  g.kind = hough_weighting_from_string(kind);
  r.read("rho_min", g.rho_min);
  r.read("min_cos_incidence", g.min_cos_incidence);
  r.finish();
  validate(g);
}

double hough_weight(const ScanPoint& p, double sensor_heading, double beta,
                    const HoughWeight& g) {
  switch (g.kind) {
    case HoughWeighting::kCount:
      return 1.0;  // (5.11)
    case HoughWeighting::kRange:
      return p.range / g.rho_min;  // (5.10)
    case HoughWeighting::kRangeIncidence: {
      // (5.8): |cos| floored, see the header.
      const double c = std::abs(std::cos(sensor_heading + p.bearing - beta));
      return p.range / g.rho_min / std::max(c, g.min_cos_incidence);
    }
  }
  return 0.0;
}

double hough_score(std::span<const ScanPoint> points, double sensor_heading,
                   const LineParams& line, const HoughOptions& o) {
  validate(o);
  const double cb = std::cos(line.beta), sb = std::sin(line.beta);
  double c = 0.0;
  for (const ScanPoint& p : points) {
    const double x = p.world.x() * cb + p.world.y() * sb - line.rho;  // (5.4)
    if (rectangular_window(x, o.d_limit) == 0.0) continue;            // (5.7)
    c += hough_weight(p, sensor_heading, line.beta, o.g);              // (5.6)
  }
  return c;
}

}  // namespace locbench::laser
