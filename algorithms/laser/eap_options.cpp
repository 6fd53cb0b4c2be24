// EapOptions (eap_matcher.h): validation and JSON, apart from the matcher's work.
#include <cmath>
#include <string>

#include "algorithms/laser/eap_matcher.h"
#include "core/enum_names.h"
#include "core/errors.h"
#include "core/option_fields.h"
#include "core/units.h"

namespace locbench::laser {

constexpr EnumNames<ClaimOrder, 2> kClaimOrders{
    {{ClaimOrder::kNearestSegment, "nearest_segment"}, {ClaimOrder::kMapOrder, "map_order"}}};

const char* to_string(ClaimOrder c) { return enum_name(kClaimOrders, c); }
ClaimOrder claim_order_from_string(const std::string& s) { return enum_value(kClaimOrders, s, "claim_order must be"); }

// EapOptions' fields, stated once (eap_matcher.h explains each).
template <class V>
void visit_fields(V& v, EapOptions& o) {
  v.field("d_limit", o.d_limit, "m", positive(), "half-width of ω2 (5.5)");
  v.field("c_limit", o.c_limit, "", non_negative(), "minimum score Σg of a run (§5.3: 5)");
  v.field("min_extent", o.min_extent, "m", non_negative(), "a run's first-to-last distance must exceed this");
  v.field("max_direction_error", o.max_direction_error, "rad", closed_open(0.0, kPi / 2),
          "ours: chord-to-segment angle limit (0 = off, the thesis)");
  v.field("trim_distance", o.trim_distance, "m", non_negative(),
          "ours: drop the farthest point while beyond this, then refit (0 = off, the thesis)");
  v.nested("weighting", o.weighting, "g of 5.8/5.10/5.11 (HoughWeight)");
  v.flag("remove_claimed", o.remove_claimed, "§5.3: delete matched points");
  v.choice("claim_order", o.claim_order, to_string, claim_order_from_string, "\"nearest_segment\" or \"map_order\"");
  v.choice("region", o.region, to_string, region_rule_from_string, "ω1: \"thesis\" or \"stadium\" (eap_region.h)");
}

void validate(const EapOptions& o) { validate_fields(o, "EapOptions"); }

LOCBENCH_OPTIONS_JSON(EapOptions)

std::string eap_options_table() { return fields_markdown(describe_fields<EapOptions>()); }

}  // namespace locbench::laser
