#include "baselines/laser/options_json.h"

#include "core/json_options.h"
#include "baselines/laser/extraction_steps.h"

namespace locbench::laser {
namespace {

template <class MatcherOptions>
void matcher_to_json(nlohmann::json& j, const MatcherOptions& o) {
  j = {{"extraction", o.extraction}, {"matching", o.matching}};
}

template <class MatcherOptions>
void matcher_from_json(const nlohmann::json& j, MatcherOptions& o, const char* what) {
  StrictJsonReader r(j, what);
  r.read_object("extraction", o.extraction);
  r.read_object("matching", o.matching);
  r.finish();
}

}  // namespace

void to_json(nlohmann::json& j, const BreakpointOptions& o) {
  j = {{"lambda", o.lambda}, {"range_sigma", o.range_sigma}};
}
void from_json(const nlohmann::json& j, BreakpointOptions& o) {
  StrictJsonReader r(j, "BreakpointOptions");
  r.read("lambda", o.lambda);
  r.read("range_sigma", o.range_sigma);
  r.finish();
  detail::validate(o, "BreakpointOptions");
}

void to_json(nlohmann::json& j, const LineAcceptance& o) {
  j = {{"min_points", o.min_points}, {"min_length", o.min_length}};
}
void from_json(const nlohmann::json& j, LineAcceptance& o) {
  StrictJsonReader r(j, "LineAcceptance");
  int min_points = static_cast<int>(o.min_points);
  r.read("min_points", min_points);
  r.read("min_length", o.min_length);
  r.finish();
  if (min_points < 2) r.fail("min_points", "must be >= 2");
  o.min_points = static_cast<std::size_t>(min_points);
  detail::validate(o, "LineAcceptance");
}

void to_json(nlohmann::json& j, const SplitAndMergeOptions& o) {
  j = {{"breakpoints", o.breakpoints},
       {"acceptance", o.acceptance},
       {"split_distance", o.split_distance}};
}
void from_json(const nlohmann::json& j, SplitAndMergeOptions& o) {
  StrictJsonReader r(j, "SplitAndMergeOptions");
  r.read_object("breakpoints", o.breakpoints);
  r.read_object("acceptance", o.acceptance);
  r.read("split_distance", o.split_distance);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const AgglomerativeOptions& o) {
  j = {{"breakpoints", o.breakpoints},
       {"acceptance", o.acceptance},
       {"window", o.window},
       {"window_confidence", o.window_confidence},
       {"merge_confidence", o.merge_confidence},
       {"model_sigma_alpha", o.model_sigma_alpha},
       {"model_sigma_r", o.model_sigma_r},
       {"assign_distance", o.assign_distance},
       {"max_gap_points", o.max_gap_points}};
}
void from_json(const nlohmann::json& j, AgglomerativeOptions& o) {
  StrictJsonReader r(j, "AgglomerativeOptions");
  r.read_object("breakpoints", o.breakpoints);
  r.read_object("acceptance", o.acceptance);
  r.read("window", o.window);
  r.read("window_confidence", o.window_confidence);
  r.read("merge_confidence", o.merge_confidence);
  r.read("model_sigma_alpha", o.model_sigma_alpha);
  r.read("model_sigma_r", o.model_sigma_r);
  r.read("assign_distance", o.assign_distance);
  r.read("max_gap_points", o.max_gap_points);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const RwhtOptions& o) {
  j = {{"breakpoints", o.breakpoints},         {"acceptance", o.acceptance},
       {"angle_bin", o.angle_bin},             {"range_bin", o.range_bin},
       {"min_peak_votes", o.min_peak_votes},   {"nms_radius", o.nms_radius},
       {"inlier_distance", o.inlier_distance}, {"max_gap_points", o.max_gap_points}};
}
void from_json(const nlohmann::json& j, RwhtOptions& o) {
  StrictJsonReader r(j, "RwhtOptions");
  r.read_object("breakpoints", o.breakpoints);
  r.read_object("acceptance", o.acceptance);
  r.read("angle_bin", o.angle_bin);
  r.read("range_bin", o.range_bin);
  r.read("min_peak_votes", o.min_peak_votes);
  r.read("nms_radius", o.nms_radius);
  r.read("inlier_distance", o.inlier_distance);
  r.read("max_gap_points", o.max_gap_points);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const LineMatchOptions& o) {
  j = {{"max_delta_rho", o.max_delta_rho},
       {"max_delta_beta", o.max_delta_beta},
       {"min_overlap", o.min_overlap},
       {"end_tolerance", o.end_tolerance}};
}
void from_json(const nlohmann::json& j, LineMatchOptions& o) {
  StrictJsonReader r(j, "LineMatchOptions");
  r.read("max_delta_rho", o.max_delta_rho);
  r.read("max_delta_beta", o.max_delta_beta);
  r.read("min_overlap", o.min_overlap);
  r.read("end_tolerance", o.end_tolerance);
  r.finish();
  validate(o);
}

void to_json(nlohmann::json& j, const SplitAndMergeMatcherOptions& o) { matcher_to_json(j, o); }
void from_json(const nlohmann::json& j, SplitAndMergeMatcherOptions& o) {
  matcher_from_json(j, o, "SplitAndMergeMatcherOptions");
}
void to_json(nlohmann::json& j, const AgglomerativeMatcherOptions& o) { matcher_to_json(j, o); }
void from_json(const nlohmann::json& j, AgglomerativeMatcherOptions& o) {
  matcher_from_json(j, o, "AgglomerativeMatcherOptions");
}
void to_json(nlohmann::json& j, const RwhtMatcherOptions& o) { matcher_to_json(j, o); }
void from_json(const nlohmann::json& j, RwhtMatcherOptions& o) {
  matcher_from_json(j, o, "RwhtMatcherOptions");
}

}  // namespace locbench::laser
