#pragma once
// The g-weighted Hough transform of §5.3: the score of a map line (ρ, β) given a scan,
//   c(ρ, β) = Σ_i w(x_G(i) cosβ + y_G(i) sinβ − ρ) · g(ρ_i, α_i, β)            (5.6)
// with the rectangular window w(x) = 1 if |x| ≤ d_limit, else 0                (5.7)
// and one of three weightings g:
//   kRangeIncidence  g = (ρ_i/ρ_min) · 1/cos(α_i + θ(k) − β)                  (5.8, 5.9)
//   kRange           g = ρ_i/ρ_min                                            (5.10)
//   kCount           g ≡ 1: c counts the points within d_limit of the line     (5.11, the one
//                                                                             the thesis uses)
// Deviations, both because (5.8) is unbounded as printed: the cosine is taken in absolute value
// (with ρ ≥ 0 the normal may point towards or away from the sensor, and a beam meets the plane
// the same way either way), and floored at `min_cos_incidence` (grazing beams would otherwise
// weigh ∞ — the thesis's own objection (3) to 5.9). ρ_min (the closest the robot lets the laser
// come to an obstacle) has no value in the thesis; 0.5 m is ours.
// α_i + θ(k) is the beam's world direction; with a sensor mount it is θ(k) + mount θ + bearing.
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "algorithms/laser/scan_points.h"
#include "core/segment.h"

namespace locbench::laser {

enum class HoughWeighting { kCount, kRange, kRangeIncidence };
const char* to_string(HoughWeighting w);
// "count" | "range" | "range_incidence"; throws UsageError otherwise.
HoughWeighting hough_weighting_from_string(const std::string& s);

// The weighting g and its constants.
struct HoughWeight {
  HoughWeighting kind = HoughWeighting::kCount;  // the thesis's choice (5.11)
  double rho_min = 0.5;                          // [m] ρ_min of 5.8/5.10 (not given; ours)
  double min_cos_incidence = 0.05;               // floor of |cos| in 5.8 (≈ 87° incidence)
};
// Throws UsageError naming the field: rho_min finite > 0, min_cos_incidence in (0, 1].
void validate(const HoughWeight& g);
void to_json(nlohmann::json& j, const HoughWeight& g);
// Strict: unknown keys, wrong types or invalid values throw UsageError.
void from_json(const nlohmann::json& j, HoughWeight& g);

struct HoughOptions {
  double d_limit = 0.200;  // [m] half-width of the window w (5.7); §5.3 takes 200 mm
  HoughWeight g;
};
void validate(const HoughOptions& o);

// w(x) (5.7).
inline double rectangular_window(double x, double d_limit) { return (x <= d_limit && x >= -d_limit) ? 1.0 : 0.0; }

// g of one point against a line of normal direction β (5.8, 5.10 or 1). `sensor_heading` is
// the world heading of the sensor's x axis under the estimate (θ(k) + mount θ).
double hough_weight(const ScanPoint& p, double sensor_heading, double beta, const HoughWeight& g);

// c(ρ, β) over `points` (their `world` coordinates under the estimate) (5.6).
double hough_score(std::span<const ScanPoint> points, double sensor_heading, const LineParams& line,
                   const HoughOptions& o);

}  // namespace locbench::laser
