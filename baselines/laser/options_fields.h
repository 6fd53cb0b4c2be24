#pragma once
// The laser baselines' options, each field stated once (name, unit, allowed range, meaning;
// the struct headers explain the defaults). The visitors give JSON (options_json.cpp), the
// range checks of each validate() and the docs table (core/option_fields.h).
#include "baselines/laser/extract_then_match.h"
#include "core/option_fields.h"
#include "core/units.h"

namespace locbench::baselines::laser {

template <class V>
void visit_fields(V& v, BreakpointOptions& o) {
  v.field("lambda", o.lambda, "rad", open(0.0, kPi / 2), "breakpoint angle λ");
  v.field("range_sigma", o.range_sigma, "m", non_negative(), "σ_r of a range");
}

template <class V>
void visit_fields(V& v, LineAcceptance& o) {
  v.field("min_points", o.min_points, "", at_least(2), "points of an accepted line");
  v.field("min_length", o.min_length, "m", non_negative(), "first-to-last length of an accepted line");
}

template <class V>
void visit_fields(V& v, SplitAndMergeOptions& o) {
  v.nested("breakpoints", o.breakpoints, "BreakpointOptions");
  v.nested("acceptance", o.acceptance, "LineAcceptance");
  v.field("split_distance", o.split_distance, "m", positive(), "largest residual a line may keep");
}

template <class V>
void visit_fields(V& v, AgglomerativeOptions& o) {
  v.nested("breakpoints", o.breakpoints, "BreakpointOptions");
  v.nested("acceptance", o.acceptance, "LineAcceptance");
  v.field("window", o.window, "points", at_least(3), "points per local line");
  v.field("window_confidence", o.window_confidence, "", open(0.0, 1.0), "χ² confidence of a local line");
  v.field("merge_confidence", o.merge_confidence, "", open(0.0, 1.0), "χ²(2) confidence of a merge");
  v.field("model_sigma_alpha", o.model_sigma_alpha, "rad", non_negative(), "added σ of a cluster's α");
  v.field("model_sigma_r", o.model_sigma_r, "m", non_negative(), "added σ of a cluster's r");
  v.field("assign_distance", o.assign_distance, "m", non_negative(), "point-to-line distance of a member");
  v.field("max_gap_points", o.max_gap_points, "points", non_negative(), "points a line may skip");
}

template <class V>
void visit_fields(V& v, RwhtOptions& o) {
  v.nested("breakpoints", o.breakpoints, "BreakpointOptions");
  v.nested("acceptance", o.acceptance, "LineAcceptance");
  v.field("angle_bin", o.angle_bin, "rad", open_closed(0.0, kPi), "accumulator angle bin");
  v.field("range_bin", o.range_bin, "m", positive(), "accumulator range bin");
  v.field("min_peak_votes", o.min_peak_votes, "m", non_negative(), "range-weighted votes of a peak");
  v.field("nms_radius", o.nms_radius, "bins", at_least(1), "non-maximum suppression radius");
  v.field("inlier_distance", o.inlier_distance, "m", positive(), "point-to-line distance of an inlier");
  v.field("max_gap_points", o.max_gap_points, "points", non_negative(), "points a line may skip");
}

template <class V>
void visit_fields(V& v, LineMatchOptions& o) {
  v.field("max_delta_rho", o.max_delta_rho, "m", positive(), "largest ρ difference of a match");
  v.field("max_delta_beta", o.max_delta_beta, "rad", open_closed(0.0, kPi), "largest β difference of a match");
  v.field("min_overlap", o.min_overlap, "", open_closed(0.0, 1.0), "overlap, fraction of the extracted segment");
  v.field("end_tolerance", o.end_tolerance, "m", non_negative(), "slack at the map segment's ends");
}

// The matchers: {"extraction": {...}, "matching": {...}}.
template <class V, class Extraction>
void visit_fields(V& v, ExtractThenMatchOptions<Extraction>& o) {
  v.nested("extraction", o.extraction, "the extractor's options");
  v.nested("matching", o.matching, "LineMatchOptions");
}

}  // namespace locbench::baselines::laser
