// EapOptions (eap_matcher.h): validation and JSON, apart from the matcher's work.
#include <cmath>
#include <string>

#include "core/errors.h"
#include "core/json_options.h"
#include "core/units.h"
#include "algorithms/laser/eap_matcher.h"

namespace locbench::laser {

const char* to_string(ClaimOrder c) {
  switch (c) {
    case ClaimOrder::kNearestSegment: return "nearest_segment";
    case ClaimOrder::kMapOrder: return "map_order";
  }
  return "?";
}

ClaimOrder claim_order_from_string(const std::string& s) {
  if (s == "nearest_segment") return ClaimOrder::kNearestSegment;
  if (s == "map_order") return ClaimOrder::kMapOrder;
  throw UsageError("claim_order must be \"nearest_segment\" or \"map_order\", got \"" + s + "\"");
}

void validate(const EapOptions& o) {
  if (!(std::isfinite(o.d_limit) && o.d_limit > 0.0)) {
    throw UsageError("EapOptions.d_limit must be finite and > 0");
  }
  if (!(std::isfinite(o.c_limit) && o.c_limit >= 0.0)) {
    throw UsageError("EapOptions.c_limit must be finite and ≥ 0");
  }
  if (!(std::isfinite(o.min_extent) && o.min_extent >= 0.0)) {
    throw UsageError("EapOptions.min_extent must be finite and ≥ 0");
  }
  if (!(std::isfinite(o.trim_distance) && o.trim_distance >= 0.0)) {
    throw UsageError("EapOptions.trim_distance must be finite and ≥ 0 (0 = off)");
  }
  if (!(o.max_direction_error >= 0.0 && o.max_direction_error < kPi / 2)) {
    throw UsageError("EapOptions.max_direction_error must be in [0, π/2) rad (0 = off)");
  }
  try {
    validate(o.weighting);
  } catch (const UsageError& e) {
    throw UsageError(std::string("EapOptions.weighting: ") + e.what());
  }
}

void to_json(nlohmann::json& j, const EapOptions& o) {
  nlohmann::json g;
  to_json(g, o.weighting);
  j = {{"d_limit", o.d_limit},
       {"c_limit", o.c_limit},
       {"min_extent", o.min_extent},
       {"max_direction_error", o.max_direction_error},
       {"trim_distance", o.trim_distance},
       {"weighting", g},
       {"remove_claimed", o.remove_claimed},
       {"claim_order", to_string(o.claim_order)},
       {"region", to_string(o.region)}};
}

void from_json(const nlohmann::json& j, EapOptions& o) {
  StrictJsonReader r(j, "EapOptions");
  r.read("d_limit", o.d_limit);
  r.read("c_limit", o.c_limit);
  r.read("min_extent", o.min_extent);
  r.read("max_direction_error", o.max_direction_error);
  r.read("trim_distance", o.trim_distance);
  r.read_object("weighting", o.weighting);
  r.read("remove_claimed", o.remove_claimed);
  std::string order = to_string(o.claim_order), region = to_string(o.region);
  r.read("claim_order", order);
  r.read("region", region);
  r.finish();
  try {
    o.claim_order = claim_order_from_string(order);
    o.region = region_rule_from_string(region);
  } catch (const UsageError& e) {
    r.fail("", e.what());
  }
  validate(o);
}

}  // namespace locbench::laser
