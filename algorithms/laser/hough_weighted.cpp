#include "algorithms/laser/hough_weighted.h"

#include <algorithm>
#include <cmath>

#include "core/enum_names.h"
#include "core/errors.h"
#include "core/option_fields.h"

namespace locbench::laser {

constexpr EnumNames<HoughWeighting, 3> kHoughWeightings{{{HoughWeighting::kCount, "count"},
                                                         {HoughWeighting::kRange, "range"},
                                                         {HoughWeighting::kRangeIncidence, "range_incidence"}}};

const char* to_string(HoughWeighting w) { return enum_name(kHoughWeightings, w); }
HoughWeighting hough_weighting_from_string(const std::string& s) {
  return enum_value(kHoughWeightings, s, "weighting must be");
}

// HoughWeight's fields, stated once (hough_weighted.h explains each).
template <class V>
void visit_fields(V& v, HoughWeight& g) {
  v.choice("kind", g.kind, to_string, hough_weighting_from_string,
           "\"count\" (5.11), \"range\" (5.10) or \"range_incidence\" (5.8)");
  v.field("rho_min", g.rho_min, "m", positive(), "ρ_min of 5.8/5.10");
  v.field("min_cos_incidence", g.min_cos_incidence, "", open_closed(0.0, 1.0), "floor of |cos| in 5.8");
}

void validate(const HoughWeight& g) { validate_fields(g, "HoughWeight"); }

void validate(const HoughOptions& o) {
  if (!(std::isfinite(o.d_limit) && o.d_limit > 0.0)) {
    throw UsageError("HoughOptions.d_limit must be finite and > 0");
  }
  validate(o.g);
}

LOCBENCH_OPTIONS_JSON(HoughWeight)

double hough_weight(const ScanPoint& p, double sensor_heading, double beta, const HoughWeight& g) {
  switch (g.kind) {
    case HoughWeighting::kCount: return 1.0;                  // (5.11)
    case HoughWeighting::kRange: return p.range / g.rho_min;  // (5.10)
    case HoughWeighting::kRangeIncidence: {
      // (5.8): |cos| floored, see the header.
      const double c = std::abs(std::cos(sensor_heading + p.bearing - beta));
      return p.range / g.rho_min / std::max(c, g.min_cos_incidence);
    }
  }
  return 0.0;
}

double hough_score(std::span<const ScanPoint> points, double sensor_heading, const LineParams& line,
                   const HoughOptions& o) {
  validate(o);
  const double cb = std::cos(line.beta), sb = std::sin(line.beta);
  double c = 0.0;
  for (const ScanPoint& p : points) {
    const double x = p.world.x() * cb + p.world.y() * sb - line.rho;  // (5.4)
    if (rectangular_window(x, o.d_limit) == 0.0) continue;            // (5.7)
    c += hough_weight(p, sensor_heading, line.beta, o.g);             // (5.6)
  }
  return c;
}

}  // namespace locbench::laser
